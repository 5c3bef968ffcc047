#include "quadtri/mesh/topology.h"

#include <algorithm>
#include <atomic>
#include <mutex>

#include "quadtri/math/error.h"
#include "quadtri/math/large_array.h"
#include "quadtri/math/parallel.h"

namespace quadtri {

MeshTopology::MeshTopology(const TriangleMesh& mesh) {
  const size_t triangles = mesh.triangles.size();
  const size_t halves = 3 * triangles;
  const size_t vertices = mesh.positions.size();
  // Half-edge h = 3t + k joins vertices lower(h) <= upper(h). Ordered by (lower, upper, h) the
  // half-edges of one edge are adjacent, least h first. A counting sort on lower puts the
  // entries (upper, h) in one bucket per vertex, in increasing h; each bucket (about six
  // entries on a closed mesh) is then sorted. That order does not depend on the thread count,
  // and it takes linear time.
  const auto ends = [&](size_t h) {
    const Tri& tri = mesh.triangles[h / 3];
    const int k = int(h % 3);
    const uint32_t a = tri[k], b = tri[(k + 1) % 3];
    return a < b ? std::pair(a, b) : std::pair(b, a);
  };
  std::vector<uint32_t> start = largeVector<uint32_t>(vertices + 1, 0);
  for (size_t h = 0; h < halves; ++h) {
    const auto [a, b] = ends(h);
    if (b >= vertices)
      fail("triangle {}: vertex index {} is out of range (the mesh has {} vertices)", h / 3, b,
           vertices);
    ++start[a + 1];
  }
  for (size_t v = 0; v < vertices; ++v) start[v + 1] += start[v];
  // entry = upper << 32 | h: sorting a bucket's entries sorts it by (upper, h).
  std::vector<uint64_t> entries = largeVector<uint64_t>(halves);
  {
    std::vector<uint32_t> fill;
    reserveLarge(fill, vertices);
    fill.assign(start.begin(), start.end() - 1);
    for (size_t h = 0; h < halves; ++h) {
      const auto [a, b] = ends(h);
      entries[fill[a]++] = (uint64_t(b) << 32) | h;
    }
  }
  const auto upperOf = [](uint64_t entry) { return uint32_t(entry >> 32); };
  const auto halfOf = [](uint64_t entry) { return uint32_t(entry); };
  // Each bucket's edges: runs of one upper. groupSize[h] is the number of sides of the edge
  // whose least half-edge is h, 0 for every other h. Buckets are independent.
  std::vector<uint32_t> groupSize = largeVector<uint32_t>(halves, 0);
  const auto forEachEdge = [&](size_t v, const auto& f) {
    const uint64_t* first = entries.data() + start[v];
    const uint64_t* last = entries.data() + start[v + 1];
    for (const uint64_t* i = first; i < last;) {
      const uint64_t* j = i + 1;
      while (j < last && upperOf(*j) == upperOf(*i)) ++j;
      f(i, j);
      i = j;
    }
  };
  parallelForRange(tbb::blocked_range<size_t>(0, vertices, 4096),
                   [&](const tbb::blocked_range<size_t>& range) {
                     for (size_t v = range.begin(); v != range.end(); ++v) {
                       std::sort(entries.data() + start[v], entries.data() + start[v + 1]);
                       forEachEdge(v, [&](const uint64_t* i, const uint64_t* j) {
                         groupSize[halfOf(*i)] = uint32_t(j - i);
                       });
                     }
                   });
  // Edges are numbered in the order of their least half-edge; offset[e] is where edge e's
  // sides begin in sides_.
  std::vector<uint32_t> edgeId = largeVector<uint32_t>(halves, 0);
  std::vector<size_t> offset(1, 0);
  reserveLarge(offset, halves / 2 + 2);
  for (size_t h = 0; h < halves; ++h)
    if (groupSize[h] > 0) {
      edgeId[h] = uint32_t(offset.size() - 1);
      offset.push_back(offset.back() + groupSize[h]);
    }
  const size_t edgeCount = offset.size() - 1;
  resizeLarge(edges, edgeCount);
  resizeLarge(sides_, halves);
  resizeLarge(edgeOf, triangles);
  parallelForRange(tbb::blocked_range<size_t>(0, vertices, 4096),
                   [&](const tbb::blocked_range<size_t>& range) {
                     for (size_t v = range.begin(); v != range.end(); ++v)
                       forEachEdge(v, [&](const uint64_t* i, const uint64_t* j) {
                         const uint32_t e = edgeId[halfOf(*i)];
                         Edge& edge = edges[e];
                         edge.a = uint32_t(v);
                         edge.b = upperOf(*i);
                         EdgeSide* side = sides_.data() + offset[e];
                         for (const uint64_t* g = i; g < j; ++g, ++side) {
                           const uint32_t h = halfOf(*g);
                           *side = EdgeSide(h / 3, uint8_t(h % 3));
                           edgeOf[h / 3][h % 3] = e;
                         }
                         edge.sides = EdgeSides(sides_.data() + offset[e], side);
                       });
                   });
}

size_t MeshTopology::boundaryEdgeCount() const {
  return std::count_if(edges.begin(), edges.end(),
                       [](const Edge& e) { return e.sides.size() == 1; });
}

size_t MeshTopology::nonManifoldEdgeCount() const {
  return std::count_if(edges.begin(), edges.end(),
                       [](const Edge& e) { return e.sides.size() > 2; });
}

struct TopologyCache::State {
  mutable std::mutex mutex;
  std::shared_ptr<const MeshTopology> topology;
  /// The triangle array it was built from: a mesh whose array moved or resized is rebuilt.
  const Tri* data = nullptr;
  size_t count = 0;
  std::atomic<size_t> builds{0};

  bool holds(const TriangleMesh& mesh) const {
    return topology && data == mesh.triangles.data() && count == mesh.triangles.size();
  }
};

TopologyCache::TopologyCache() : state_(std::make_unique<State>()) {}
TopologyCache::~TopologyCache() = default;
TopologyCache::TopologyCache(const TopologyCache&) : TopologyCache() {}
TopologyCache& TopologyCache::operator=(const TopologyCache& other) {
  if (this != &other) forget();
  return *this;
}
TopologyCache::TopologyCache(TopologyCache&& other) noexcept : state_(std::move(other.state_)) {
  other.state_ = std::make_unique<State>();
}
TopologyCache& TopologyCache::operator=(TopologyCache&& other) noexcept {
  if (this != &other) {
    state_ = std::move(other.state_);
    other.state_ = std::make_unique<State>();
  }
  return *this;
}

const MeshTopology& TopologyCache::get(const TriangleMesh& mesh) const {
  {
    const std::lock_guard<std::mutex> lock(state_->mutex);
    if (state_->holds(mesh)) return *state_->topology;
  }
  // Built outside the lock: two threads asking at once may both build; the first kept wins.
  auto built = std::make_shared<const MeshTopology>(mesh);
  state_->builds.fetch_add(1, std::memory_order_relaxed);
  const std::lock_guard<std::mutex> lock(state_->mutex);
  if (!state_->holds(mesh)) {
    state_->topology = std::move(built);
    state_->data = mesh.triangles.data();
    state_->count = mesh.triangles.size();
  }
  return *state_->topology;
}

void TopologyCache::keep(const TriangleMesh& mesh, std::shared_ptr<const MeshTopology> topology) {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  state_->topology = std::move(topology);
  state_->data = mesh.triangles.data();
  state_->count = mesh.triangles.size();
}

void TopologyCache::forget() {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  state_->topology.reset();
  state_->data = nullptr;
  state_->count = 0;
}

size_t TopologyCache::builds() const {
  return state_->builds.load(std::memory_order_relaxed);
}

}  // namespace quadtri
