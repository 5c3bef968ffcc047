// Image files (EXR, PNG, and whatever else OpenImageIO reads) and text drawn into pixels go
// through a module, libquadtri_image.so, that quadtri loads the first time it needs one.
// OpenImageIO pulls in some 270 shared libraries (codecs, OpenVDB, FFmpeg, …); linked into
// every quadtri program, resolving them cost each process about 0.3 s and 130 MiB before
// main(), whether it wrote an image or not. Only the module links OpenImageIO.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace quadtri {

/// What an image file holds, or is to hold.
struct ImageFileSpec {
  int width = 0, height = 0, channels = 3;
  bool floatPixels = true;  ///< 32-bit float channels, else 8-bit unsigned
  /// The data window's origin, the display window's origin and size (0: the data window's).
  int x = 0, y = 0, fullX = 0, fullY = 0, fullWidth = 0, fullHeight = 0;
  /// Written as the file's colour space ("sRGB"); empty: none.
  std::string colorSpace;
  /// Compression, where the format has a choice ("zip"); empty: the format's default.
  std::string compression;
  /// name=value string attributes of the header (formats that keep them).
  std::vector<std::pair<std::string, std::string>> attributes;
};

/// The module's entry points. Each returns an empty string on success, else the error.
struct ImageModule {
  /// Writes interleaved pixels (spec.channels per pixel, float or 8-bit) to `path`; the format
  /// is chosen by the extension.
  std::string (*write)(const std::string& path, const ImageFileSpec& spec, const void* pixels);
  /// Reads the first subimage: `spec` gets its size, windows and string attributes, `pixels`
  /// its channels as floats (8-bit values divided by 255).
  std::string (*read)(const std::string& path, ImageFileSpec& spec, std::vector<float>& pixels);
  /// Draws `text` with the TrueType font `fontPath` into interleaved float RGB pixels: (x, y)
  /// is the left end of the baseline, or the text's centre when `centered`.
  std::string (*drawText)(float* rgb, int width, int height, int x, int y, const std::string& text,
                          int size, const std::string& fontPath, const float color[3],
                          bool centered);
};

/// The module, loaded at the first call (thread-safe): $QUADTRI_IMAGE_MODULE when set, else
/// libquadtri_image.so in lib/quadtri/ beside or above the program or library that holds this
/// code (the build tree and an installed prefix both have it there). Throws Error naming where
/// it looked when it cannot be loaded.
const ImageModule& imageModule();

}  // namespace quadtri
