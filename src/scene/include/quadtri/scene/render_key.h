// The identity of a render, for resuming it: a state saved by one render is resumed only by a
// render that would make the same image.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "quadtri/math/fnv1a.h"
#include "quadtri/render/renderer.h"
#include "quadtri/scene/scene_description.h"

namespace quadtri {

/// A 64-bit FNV-1a hash of everything the image depends on: quadtri's version, the scene
/// file's digest (FileDigest: the FNV-1a of its bytes and their count), every value of the
/// description (so included files and -D values count), the digest of every mesh file it names,
/// the model override, and the options' samples per pixel,
/// seed and reconstruction filter. A field added to SceneDescription must be added here too
/// (the scene file's bytes catch edits to the file, not -D or command-line overrides). Threads, the
/// time limit and checkpoints do not count: the image does not depend on them. Throws Error naming
/// a file it cannot read.
uint64_t renderKey(const SceneDescription& description, const RenderOptions& options,
                   const std::optional<std::string>& modelOverride);

/// renderKey of the whole film: the same for every crop window (--crop, --tile) of one render,
/// so that `quadtri merge` can tell the tiles of one render from those of another.
uint64_t filmRenderKey(const SceneDescription& description, const RenderOptions& options,
                       const std::optional<std::string>& modelOverride);

/// renderKey and filmRenderKey of one render together, reading the scene file and every mesh
/// file once for both (`quadtri render` needs both: --checkpoint/--resume and the EXR's
/// scene key).
struct RenderKeys {
  uint64_t render = 0;  ///< renderKey
  uint64_t film = 0;    ///< filmRenderKey
};
/// `files`, when given, holds the digests of files already read (BuiltScene::fileDigests, from
/// the mesh loader), so that they are not read again; the keys are the same either way.
RenderKeys renderKeys(const SceneDescription& description, const RenderOptions& options,
                      const std::optional<std::string>& modelOverride,
                      const FileDigests* files = nullptr);

/// Throws Error naming `path` unless `state` was saved by a render with this key and image
/// size.
void checkResumable(const RenderState& state, uint64_t key, int width, int height,
                    const std::string& path);

}  // namespace quadtri
