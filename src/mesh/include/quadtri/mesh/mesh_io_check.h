// Checks on a mesh file before Assimp reads it: every count its header declares must fit in
// the file, and the memory loading it would take must fit in the budget. Assimp allocates what
// a header declares before reading a single element (an OFF header of 353,535,235,358 vertices
// is an out-of-memory kill, not an error), so these checks read only the header.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace quadtri {

/// What a mesh file declares, from its header alone. OBJ has no header: its counts come from a
/// validating pass over its lines that allocates nothing per element (and names the line of a
/// bad v/vn/vt/f line or an index that refers to no element defined above it). ASCII STL has
/// none either: its facets are counted.
struct MeshFileInfo {
  /// "OBJ", "OFF", "PLY ascii", "PLY binary_little_endian", "STL ascii", "STL binary", ...
  std::string format;
  uint64_t fileBytes = 0;  ///< the file's size
  uint64_t vertices = 0;   ///< declared vertices (STL: 3 per facet, as Assimp stores them)
  uint64_t faces = 0;      ///< declared faces (polygons; STL facets)
  uint64_t corners = 0;    ///< face corners: exact for OBJ and STL, 3 per face otherwise
  /// Triangles after triangulation: exact for OBJ and STL; the declared faces otherwise (a
  /// polygon makes more, a face Assimp skips none).
  uint64_t triangles = 0;
  uint64_t normals = 0,
           texcoords = 0;      ///< OBJ's vn and vt lines (normals: also NOFF's, one per vertex)
  uint64_t otherElements = 0;  ///< PLY elements other than vertex and face
  /// Estimated peak bytes of loading the file into a TriangleMesh: the file buffer, Assimp's
  /// scene before and after its post-processing, and the welded mesh (see estimateLoadBytes).
  uint64_t loadBytes = 0;
};

/// Reads the header (OBJ: every line) and checks each declared count against the least number
/// of bytes its elements take in this format (ASCII: a digit and a separator per value; binary:
/// the sizes of the properties), so that no count can make a loader allocate more than a small
/// multiple of the file's size. Throws Error naming the file, the count and the size otherwise,
/// or a count over 2^32 - 1 (Assimp's counts are 32-bit and would wrap), or a header that is not
/// the format's. Nothing is allocated per element.
MeshFileInfo inspectMeshFile(const std::filesystem::path& path);

/// The peak bytes loadMesh needs for such a file, from its counts times the bytes per element
/// of Assimp's importer and post-processing and of TriangleMesh with its welding maps (measured
/// on Assimp 5.2; an estimate, meant to be within a factor of 2 of the peak resident memory).
uint64_t estimateLoadBytes(const MeshFileInfo& info);

/// A limit on the memory one command may use for its meshes and what it builds from them. One
/// budget may be shared by several meshes (the shapes of a scene): each charge adds to usedBytes.
struct MemoryBudget {
  uint64_t maxBytes = 0;          ///< 0: no limit
  uint64_t bytesPerTriangle = 0;  ///< what the caller builds per input triangle (its model)
  /// What the caller builds that grows with the triangles only up to a cap (the regions that
  /// quadric-g1 traces, whose count is capped): this much per triangle, at least
  /// cappedFloorBytes and at most cappedBytes per mesh (0: nothing capped).
  uint64_t cappedBytesPerTriangle = 0, cappedBytes = 0, cappedFloorBytes = 0;
  uint64_t usedBytes = 0;               ///< charged so far
  std::string option = "--max-memory";  ///< how the limit is named in errors
};

/// What the caller builds for one mesh of `triangles` triangles (saturating, never wrapping):
/// bytesPerTriangle per triangle, and cappedBytesPerTriangle more per triangle, at least
/// cappedFloorBytes, up to cappedBytes.
uint64_t modelBytes(const MemoryBudget& budget, uint64_t triangles);

/// How modelBytes is made up, for errors: "N per triangle" and, where something is capped,
/// " and M more per triangle up to C" (" and M more per triangle, at least F, up to C" with a
/// floor).
std::string describeModelBytes(const MemoryBudget& budget);

/// Charges `bytes` (described by `what`, e.g. "loading and converting 12 triangles") for
/// `name` to the budget; throws Error with the estimate and the limit when it would exceed
/// maxBytes, leaving usedBytes unchanged.
void chargeMemory(MemoryBudget& budget, uint64_t bytes, const std::string& name,
                  const std::string& what);

/// Charges what loading the file and building bytesPerTriangle per triangle takes.
void chargeMeshFile(MemoryBudget& budget, const MeshFileInfo& info,
                    const std::filesystem::path& path);

}  // namespace quadtri
