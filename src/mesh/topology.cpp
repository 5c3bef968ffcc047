#include "quadtri/mesh/topology.h"

#include <algorithm>
#include <atomic>
#include <mutex>

#include "quadtri/math/error.h"
#include "quadtri/math/parallel.h"

namespace quadtri {

MeshTopology::MeshTopology(const TriangleMesh& mesh) {
  const size_t triangles = mesh.triangles.size();
  const size_t halves = 3 * triangles;
  const size_t vertices = mesh.positions.size();
  // Half-edge h = 3t + k joins vertices lower(h) < upper(h) (or two equal ones). Ordered by
  // (lower, upper, h) the half-edges of one edge are adjacent. A counting sort on lower puts
  // them in buckets in increasing h; each bucket (about six half-edges on a closed mesh) is then
  // ordered by upper, stably. The order is the one sorting (lower, upper, h) gives, whatever
  // the thread count, in linear time and without a key array.
  const auto ends = [&](size_t h) {
    const Tri& tri = mesh.triangles[h / 3];
    const int k = int(h % 3);
    const uint32_t a = tri[k], b = tri[(k + 1) % 3];
    return a < b ? std::pair(a, b) : std::pair(b, a);
  };
  std::vector<uint32_t> start(vertices + 1, 0);
  for (size_t h = 0; h < halves; ++h) {
    const auto [a, b] = ends(h);
    if (b >= vertices)
      fail("triangle {}: vertex index {} is out of range (the mesh has {} vertices)", h / 3, b,
           vertices);
    ++start[a + 1];
  }
  for (size_t v = 0; v < vertices; ++v) start[v + 1] += start[v];
  std::vector<uint32_t> order(halves);
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t h = 0; h < halves; ++h) order[fill[ends(h).first]++] = uint32_t(h);
  }
  parallelForRange(tbb::blocked_range<size_t>(0, vertices, 4096),
                   [&](const tbb::blocked_range<size_t>& range) {
                     for (size_t v = range.begin(); v != range.end(); ++v) {
                       uint32_t* first = order.data() + start[v];
                       uint32_t* last = order.data() + start[v + 1];
                       // Insertion sort: stable, and the buckets are small.
                       for (uint32_t* i = first + 1; i < last; ++i) {
                         const uint32_t h = *i;
                         const uint32_t upper = ends(h).second;
                         uint32_t* j = i;
                         for (; j > first && ends(*(j - 1)).second > upper; --j) *j = *(j - 1);
                         *j = h;
                       }
                     }
                   });
  // leader[h]: the first half-edge (least h) of h's edge. Edges are numbered by their leader.
  std::vector<uint32_t> leader(halves);
  std::vector<uint32_t> groupSize(halves, 0);
  for (size_t i = 0; i < halves;) {
    const auto key = ends(order[i]);
    size_t j = i + 1;
    while (j < halves && ends(order[j]) == key) ++j;
    const uint32_t first = order[i];
    for (size_t g = i; g < j; ++g) leader[order[g]] = first;
    groupSize[first] = uint32_t(j - i);
    i = j;
  }
  std::vector<uint32_t> edgeId(halves, 0);
  size_t edgeCount = 0;
  for (size_t h = 0; h < halves; ++h)
    if (leader[h] == h) edgeId[h] = uint32_t(edgeCount++);
  edges.resize(edgeCount);
  std::vector<size_t> offset(edgeCount + 1, 0);
  for (size_t h = 0; h < halves; ++h)
    if (leader[h] == h) offset[edgeId[h] + 1] = groupSize[h];
  for (size_t e = 0; e < edgeCount; ++e) offset[e + 1] += offset[e];
  sides_.resize(halves);
  edgeOf.resize(triangles);
  std::vector<size_t> fill(offset.begin(), offset.end() - 1);
  for (size_t h = 0; h < halves; ++h) {
    const uint32_t e = edgeId[leader[h]];
    const uint32_t t = uint32_t(h / 3);
    const uint8_t k = uint8_t(h % 3);
    sides_[fill[e]++] = EdgeSide(t, k);
    edgeOf[t][k] = e;
    if (leader[h] == h) {
      uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      if (a > b) std::swap(a, b);
      edges[e].a = a;
      edges[e].b = b;
    }
  }
  for (size_t e = 0; e < edgeCount; ++e)
    edges[e].sides = EdgeSides(sides_.data() + offset[e], sides_.data() + offset[e + 1]);
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
