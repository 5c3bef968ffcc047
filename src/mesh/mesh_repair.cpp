#include "quadtri/mesh/mesh_repair.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>
#include <utility>
#include <vector>

#include "quadtri/math/parallel.h"
#include "quadtri/mesh/topology.h"
#include "quadtri/mesh/triangle_mesh.h"
#include "quadtri/mesh/winding.h"

namespace quadtri {

namespace {

std::string count(size_t n, const char* one, const char* many) {
  return fmt::format("{} {}", n, n == 1 ? one : many);
}

/// Zero area up to the precision the mesh was read in (`significandBits`: 24 for Assimp's
/// floats, 53 for doubles): the third vertex lies within 4 units of that precision at the
/// triangle's largest coordinate from the line of its longest edge (for doubles 16 units, above
/// the rounding of the cross product that measures it). A triangle of distinct points that lie
/// on one line stays in the mesh (it still joins its neighbours' edges), and every model gives
/// it no area of its own.
bool zeroArea(const TriangleMesh& mesh, size_t t, int significandBits) {
  double longest = 0.0, extent = 0.0;
  for (int k = 0; k < 3; ++k) {
    longest = std::max(longest, (mesh.corner(t, (k + 1) % 3) - mesh.corner(t, k)).norm());
    extent = std::max(extent, mesh.corner(t, k).cwiseAbs().maxCoeff());
  }
  const double height = longest > 0.0 ? mesh.faceCross(t).norm() / longest : 0.0;
  const double units = significandBits >= 53 ? 16.0 : 4.0;
  return height <= units * std::ldexp(extent, -std::min(significandBits, 53));
}

void keepTriangles(TriangleMesh& mesh, const std::vector<char>& keep) {
  size_t out = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (!keep[t]) continue;
    mesh.triangles[out] = mesh.triangles[t];
    if (mesh.hasNormals()) mesh.normalIndices[out] = mesh.normalIndices[t];
    ++out;
  }
  mesh.triangles.resize(out);
  if (mesh.hasNormals()) mesh.normalIndices.resize(out);
}

// Re-winds the triangles of each connected part whose winding is inconsistent: two triangles
// that share an edge of exactly two sides must run along it in opposite directions. A part is
// grown across such edges from its first triangle, each triangle labelled as keeping or
// flipping its winding relative to that first one. When both labels occur, the part takes the
// winding of most of its area; a part whose labels contradict each other (a Möbius strip) is
// left as it is and counted. Flipping swaps corners 1 and 2, so a triangle keeps its first
// corner. Only for meshes without normals (they are computed from the faces afterwards): where
// the file has normals they say which side is out, and a triangle facing away from them is the
// mesh's inconsistent corner, which analyze counts. Returns {flipped, non-orientable parts}.
std::pair<size_t, size_t> orientParts(TriangleMesh& mesh, const MeshTopology& topo) {
  if (mesh.hasNormals()) return {0, 0};
  const WindingParts w = windingParts(mesh, topo);
  size_t flipped = 0, nonOrientable = 0;
  for (size_t p = 0; p < w.parts.size(); ++p) {
    const std::vector<uint32_t>& part = w.parts[p];
    if (!w.orientable[p]) {
      ++nonOrientable;
      continue;
    }
    // Area ×2 of the triangles that wind as the part's first one, and against it.
    double with = 0.0, against = 0.0;
    for (uint32_t t : part) (w.relative[t] > 0 ? with : against) += mesh.faceCross(t).norm();
    if (std::all_of(part.begin(), part.end(), [&](uint32_t t) { return w.relative[t] > 0; }))
      continue;                                   // consistent already
    const int8_t keep = against > with ? -1 : 1;  // the winding of most of the area
    for (uint32_t t : part) {
      if (w.relative[t] == keep) continue;
      std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);
      ++flipped;
    }
  }
  return {flipped, nonOrientable};
}

}  // namespace

bool MeshRepairs::any() const {
  return replacedNormals || isolatedVertices || collapsedFaces || duplicateFaces ||
         reorientedFaces || zeroAreaFaces || nonManifoldEdges || nonOrientableParts;
}

std::string MeshRepairs::summary() const {
  std::vector<std::string> fixed, kept;
  if (replacedNormals)
    fixed.push_back(count(replacedNormals, "NaN, infinite or zero normal by its face normal",
                          "NaN, infinite or zero normals by their face normals"));
  if (collapsedFaces)
    fixed.push_back(
        count(collapsedFaces, "triangle naming a vertex twice", "triangles naming a vertex twice"));
  if (duplicateFaces)
    fixed.push_back(count(duplicateFaces, "duplicate triangle", "duplicate triangles"));
  if (isolatedVertices)
    fixed.push_back(count(isolatedVertices, "isolated vertex", "isolated vertices"));
  if (zeroAreaFaces)
    kept.push_back(count(zeroAreaFaces, "zero-area triangle", "zero-area triangles"));
  if (nonManifoldEdges)
    kept.push_back(count(nonManifoldEdges, "edge with three or more triangles",
                         "edges with three or more triangles") +
                   " (crack_rate is undefined)");
  if (nonOrientableParts)
    kept.push_back(count(nonOrientableParts, "non-orientable part (as wound)",
                         "non-orientable parts (as wound)"));
  std::string s;
  auto list = [](const std::vector<std::string>& items) {
    if (items.size() == 1) return items[0];
    return fmt::format("{} and {}", fmt::join(items.begin(), items.end() - 1, ", "), items.back());
  };
  if (!fixed.empty()) {
    // The normals are replaced, the rest removed.
    std::vector<std::string> removed(fixed.begin() + (replacedNormals ? 1 : 0), fixed.end());
    if (replacedNormals) s = "replaced " + fixed[0];
    if (!removed.empty()) s += (s.empty() ? "" : "; ") + ("removed " + list(removed));
  }
  if (reorientedFaces)
    s += (s.empty() ? "" : "; ") + ("re-wound " + count(reorientedFaces, "triangle", "triangles") +
                                    " to agree with their neighbours");
  if (!kept.empty()) s += (s.empty() ? "" : "; ") + ("kept " + list(kept));
  return s;
}

MeshRepairs repairMesh(TriangleMesh& mesh, int significandBits) {
  MeshRepairs did;
  const size_t n = mesh.triangles.size();
  std::vector<char> keep(n, 1);
  // Collapsed triangles, then duplicates by their sorted vertex triple (a stable sort keeps the
  // first of each set).
  for (size_t t = 0; t < n; ++t) {
    const Tri& f = mesh.triangles[t];
    if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) {
      keep[t] = 0;
      ++did.collapsedFaces;
    }
  }
  std::vector<std::pair<Tri, uint32_t>> sorted;
  sorted.reserve(n);
  for (size_t t = 0; t < n; ++t) {
    if (!keep[t]) continue;
    Tri key = mesh.triangles[t];
    std::sort(key.begin(), key.end());
    sorted.emplace_back(key, uint32_t(t));
  }
  parallelSort(sorted.begin(), sorted.end());  // (key, t) pairs are distinct: one order
  for (size_t i = 1; i < sorted.size(); ++i)
    if (sorted[i].first == sorted[i - 1].first) {
      keep[sorted[i].second] = 0;
      ++did.duplicateFaces;
    }
  if (did.collapsedFaces || did.duplicateFaces) keepTriangles(mesh, keep);

  // Vertices no triangle uses: removed, the rest renumbered in order.
  std::vector<uint32_t> remap(mesh.positions.size(), 0);
  for (const Tri& f : mesh.triangles)
    for (uint32_t v : f) remap[v] = 1;
  const size_t used = size_t(std::count(remap.begin(), remap.end(), 1u));
  if (used < mesh.positions.size()) {
    did.isolatedVertices = mesh.positions.size() - used;
    uint32_t next = 0;
    for (size_t v = 0; v < remap.size(); ++v) {
      if (!remap[v]) continue;
      mesh.positions[next] = mesh.positions[v];
      remap[v] = next++;
    }
    mesh.positions.resize(next);
    for (Tri& f : mesh.triangles)
      for (uint32_t& v : f) v = remap[v];
  }

  // One adjacency for both: re-winding permutes triangles' local edges but not which
  // triangles meet at an edge, so the non-manifold count holds afterwards too.
  mesh.topologyCache.forget();
  auto topo = std::make_shared<const MeshTopology>(mesh);
  std::tie(did.reorientedFaces, did.nonOrientableParts) = orientParts(mesh, *topo);
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    did.zeroAreaFaces += zeroArea(mesh, t, significandBits);
  did.nonManifoldEdges = topo->nonManifoldEdgeCount();
  // Unless a face was re-wound (its local edges renumbered), the mesh keeps this adjacency for
  // the normals, the model, its metrics and its tessellation.
  if (did.reorientedFaces == 0) mesh.topologyCache.keep(mesh, std::move(topo));

  MeshRepairs& total = mesh.repairs;
  total.isolatedVertices += did.isolatedVertices;
  total.collapsedFaces += did.collapsedFaces;
  total.duplicateFaces += did.duplicateFaces;
  total.reorientedFaces += did.reorientedFaces;
  total.nonOrientableParts = did.nonOrientableParts;
  total.zeroAreaFaces = did.zeroAreaFaces;
  total.nonManifoldEdges = did.nonManifoldEdges;
  return did;
}

std::optional<std::string> repairWarning(const TriangleMesh& mesh, std::string_view what) {
  if (!mesh.repairs.any()) return std::nullopt;
  return fmt::format("{}: {}", what, mesh.repairs.summary());
}

}  // namespace quadtri
