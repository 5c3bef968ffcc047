#include "quadtri/mesh/topology.h"

#include <algorithm>
#include <atomic>
#include <mutex>

#include "quadtri/math/parallel.h"

namespace quadtri {

MeshTopology::MeshTopology(const TriangleMesh& mesh) {
  const size_t triangles = mesh.triangles.size();
  const size_t halves = 3 * triangles;
  // Half-edge h = 3t + k, keyed by its undirected edge; sorting (key, h) pairs, all distinct,
  // gives one order whatever the thread count.
  struct Half {
    uint64_t key;
    uint32_t h;
    bool operator<(const Half& o) const { return key != o.key ? key < o.key : h < o.h; }
  };
  std::vector<Half> sorted(halves);
  parallelFor(size_t(0), triangles, [&](size_t t) {
    for (int k = 0; k < 3; ++k) {
      uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      if (a > b) std::swap(a, b);
      sorted[3 * t + k] = Half{(uint64_t(a) << 32) | b, uint32_t(3 * t + k)};
    }
  });
  parallelSort(sorted.begin(), sorted.end());
  // leader[h]: the first half-edge (least h) of h's edge. Edges are numbered by their leader.
  std::vector<uint32_t> leader(halves);
  std::vector<uint32_t> groupSize(halves, 0);
  for (size_t i = 0; i < halves;) {
    size_t j = i + 1;
    while (j < halves && sorted[j].key == sorted[i].key) ++j;
    const uint32_t first = sorted[i].h;
    for (size_t g = i; g < j; ++g) leader[sorted[g].h] = first;
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
