// A model's patches as fixed-size binary records: the layout numpy's structured arrays take
// (Python's m.patches()) and the compact binary patch file, `.qtp` (README, "Binary patch
// table"), that `quadtri convert -o x.qtp` writes and Python's read_patches reads.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "quadtri/surface/model.h"
#include "quadtri/surface/patch_record.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri {

/// One field of a record: a number (bool, int64 or float64, with list dimensions `dims`) or a
/// nested record of `children`. A variable-length list (its first dimension the longest of any
/// record) is followed by an int64 NAME_count field with its length. Fields are packed in order,
/// as numpy lays out a dtype given as a list: a bool takes 1 byte, a number 8.
struct RecordField {
  enum class Kind : uint8_t { Bool = 0, Int = 1, Float = 2, Object = 3, Unknown = 4 };
  std::string name;
  Kind kind = Kind::Unknown;
  std::vector<int64_t> dims;  ///< list dimensions; empty for a scalar
  bool variable = false;      ///< followed by NAME_count
  size_t offset = 0, countOffset = 0;
  std::vector<RecordField> children;  ///< Kind::Object
  // While records are added: a value other than a string was seen; only empty lists were seen.
  bool present = false, unknownInner = false;
  /// An empty record (the root of a layout).
  static RecordField record() {
    RecordField f;
    f.kind = Kind::Object;
    return f;
  }
};

/// The record layout of a list of JSON objects, one field per key (sorted, as nlohmann::json
/// sorts them): a number is a float64 field (int64 when every record has an integer there, bool
/// for booleans), a rectangular list of numbers a subarray, an object a nested record. A list
/// whose length varies between records is padded with zeros to the longest, with a NAME_count
/// field; "planes" (clip planes of implicit patches) is always QuadricPatch::kMaxPlanes rows of
/// 4. A float a record lacks is NaN, anything else 0. Strings and nulls are left out (nulls are
/// NaN where the key is a number in another record).
class RecordLayout {
 public:
  /// Adds one record's keys and shapes; throws Error for a key whose shapes disagree.
  void add(const PatchRecord& record);
  /// The same for a JSON object (strings are left out).
  void add(const nlohmann::json& record);
  /// Adds the keys and shapes of `later`, a layout of the records that follow this one's
  /// (before either is finished): the same layout as adding those records here one by one,
  /// for records without nulls (a null is ignored where its key was seen before and makes a
  /// float field where the key is new, so its effect depends on the order: sawNull() says when
  /// that arose, and the caller adds the records one by one instead). Lets a layout be built
  /// in parallel, part by part.
  void merge(const RecordLayout& later);
  /// Whether a record added had a null value.
  bool sawNull() const { return sawNull_; }
  /// Fixes shapes and offsets; call once after the last add.
  void finish();
  size_t itemSize() const { return itemSize_; }
  const RecordField& root() const { return root_; }
  /// Writes `record` into itemSize() bytes at `out` (which it zeroes first).
  void fill(const PatchRecord& record, char* out) const;
  void fill(const nlohmann::json& record, char* out) const;

  /// The layout a field list describes (as read from a file); offsets follow from packing.
  static RecordLayout fromFields(RecordField root);

 private:
  RecordField root_ = RecordField::record();
  size_t itemSize_ = 0;
  bool sawNull_ = false;
};

/// What a bridge record holds when a model has no bridges (so the table still has its fields).
const nlohmann::json& emptyBridgeRecord();

/// What a patch table's header says besides its layouts.
struct PatchTableInfo {
  std::string model, tessellation;  ///< the model's name; "thesis" or the lattice level
  uint64_t triangles = 0;           ///< input triangles
  uint64_t patchCount = 0, bridgeCount = 0;
};

/// The header of a patch table: the fixed part, the texts, both field lists, zero padding to a
/// multiple of 8 bytes (README, "Binary patch table").
std::string patchTableHeader(const PatchTableInfo& info, const RecordLayout& patches,
                             const RecordLayout& bridges);

/// Writes the model's patch table (`.qtp`) to `out`: the header, the field lists, then one
/// record per patch and per edge bridge, little-endian. Each patch's record (patch_record.h) is
/// computed twice, a few thousand at a time (once for the layout, in parallel parts of 256, once
/// for the bytes), so the table is never held whole in memory.
void writePatchTable(const SurfaceModel& model, const Tessellation& tessellation,
                     std::ostream& out);

/// A patch table read back: its header and the records' bytes.
struct PatchTable : PatchTableInfo {
  RecordLayout patchLayout, bridgeLayout;
  std::vector<char> patches, bridges;  ///< patchCount × itemSize, bridgeCount × itemSize
};

/// Reads a `.qtp` file; throws Error naming the file and the byte offset of what is wrong (a
/// wrong magic or version, a truncated header, a malformed field list, a record size that is not
/// its fields', a size that is not the header's counts).
PatchTable readPatchTable(const std::filesystem::path& path);

}  // namespace quadtri
