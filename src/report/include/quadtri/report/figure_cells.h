// A figure split across processes: `quadtri figure --shard I/N --cells DIR` renders every model
// of its share of the rows (side by side, so each row's render-time ratios are still measured in
// one process) and saves each cell as an EXR that carries its measurements; `quadtri figure
// --from DIR...` reads the cells back and composes the grid, CSV and ratio plot exactly as a
// one-shot run does.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "quadtri/report/figure.h"

namespace quadtri {

/// EXR string attributes of a saved cell.
namespace figure_attribute {
inline constexpr const char* kSettings = "quadtri_figure_settings";  ///< figureSettingsText
inline constexpr const char* kShape = "quadtri_figure_shape";
inline constexpr const char* kModel = "quadtri_figure_model";
inline constexpr const char* kBuildSeconds = "quadtri_figure_build_s";
inline constexpr const char* kRenderTimes = "quadtri_figure_render_times_s";  ///< ';'-separated
inline constexpr const char* kSamples = "quadtri_figure_spp";  ///< mean samples per pixel
inline constexpr const char* kPrimitives = "quadtri_figure_primitives";
inline constexpr const char* kGeometryBytes = "quadtri_figure_geometry_bytes";
inline constexpr const char* kShard = "quadtri_figure_shard";  ///< "I/N" that rendered it
}  // namespace figure_attribute

/// What makes the cells of one figure: the setup, the rows and columns, -D, --spp, --seed,
/// --time, the normals override and the repeats (not --threads, which does not change the
/// images, nor the shard). Every cell carries it; cells that differ are refused.
std::string figureSettingsText(const FigureRequest& request, const std::string& setup);

/// Writes `cell` as DIR/SHAPE__MODEL.exr (atomically) with its figure_attribute values.
void saveFigureCell(const FigureCell& cell, const std::string& settingsText,
                    const std::filesystem::path& dir, const Shard& shard = {});

/// Reads the cells saved in `dirs` (every .exr there) and returns those of `request`'s grid,
/// row-major as renderFigureCells returns them. Throws Error, writing nothing, naming the file
/// whose settings differ from `settingsText` (and the first key that differs), a cell found in
/// two files, or the cells no folder holds, with the --shard I/N that renders each (of
/// `shardCount` shards, or of the count the cells found say when that is 0).
std::vector<FigureCell> loadFigureCells(const FigureRequest& request,
                                        const std::string& settingsText,
                                        const std::vector<std::filesystem::path>& dirs,
                                        size_t shardCount = 0);

}  // namespace quadtri
