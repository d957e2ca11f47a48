#pragma once
// The binary encodings of write_vtu (io/vtu_writer.hpp): every DataArray is
// format="appended" with an offset into one <AppendedData encoding="raw"> block
// at the end of the file. Internal to the io layer; the layout is:
//
//   <AppendedData encoding="raw">
//      _<array 0><array 1>...
//   </AppendedData>
//
// the offset of an array counting bytes from just after the '_' marker. The file's
// <VTKFile> element says header_type="UInt64", so every count below is a UInt64 in
// the file's byte_order (VTK "VTK File Formats", "Appended Data"; read by
// vtkXMLDataParser::ReadAppendedData and meshio's _vtu.py):
//  * raw ("binary"): <byte count of the data><data>;
//  * zlib (the <VTKFile> also says compressor="vtkZLibDataCompressor"): the data is
//    cut into blocks of kZlibBlockSize bytes (the last one may be shorter), each
//    compressed alone with zlib's compress2; the array is then
//    <number of blocks><block size><size of the last block if partial, else 0>
//    <compressed size of block 0>...<compressed size of block n-1><blocks>
//    (vtkXMLWriter::WriteBinaryDataInternal writes this header; a 0 "last size"
//    means the last block is full, as vtkXMLDataParser reads it).
#include "io/atomic_file.hpp"
#include "io/vtu_writer.hpp"
#include "mesh/mesh.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace hofem::detail {

/// vtkXMLWriter's default block size (its BlockSize, 32 KiB): readers allocate one
/// block at a time, and the blocks compress independently (in parallel here).
inline constexpr std::uint64_t kZlibBlockSize = 1u << 15;

/// The bytes of a VTK XML appended block, collected array by array.
class AppendedData {
 public:
  explicit AppendedData(bool compress) : compress_(compress) {}

  /// Adds an array and returns its offset attribute. Raw: `bytes` is referenced,
  /// not copied, and must stay valid until write_to. zlib: compressed at once.
  std::uint64_t add(std::string_view bytes);

  /// Writes the <AppendedData> element (from its indentation to its closing tag).
  void write_to(AtomicFile& file) const;

 private:
  struct Entry {
    std::string header;  // the UInt64 counts before the data
    std::string_view data;
    std::string compressed;  // zlib: the blocks (data then views it)
  };
  bool compress_;
  std::vector<Entry> entries_;
  std::uint64_t size_ = 0;
};

/// XML attribute text: field names and file names may hold any character.
std::string xml_escape(std::string_view s);

/// Writes `mesh` (checked by write_vtu) with appended binary arrays, raw or zlib.
/// `perm` and `vtk_type` are gmsh_to_vtk_permutation and vtk_cell_type of the mesh.
void write_vtu_appended(const std::string& path, const Mesh& mesh, const std::vector<int>& perm, int vtk_type,
                        const std::vector<VtuField>& point_fields, const std::vector<VtuField>& cell_fields,
                        bool compress);

}  // namespace hofem::detail
