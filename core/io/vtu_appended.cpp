#include "io/vtu_appended.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace hofem::detail {

namespace {

static_assert(std::endian::native == std::endian::little || std::endian::native == std::endian::big,
              "byte_order is written as LittleEndian or BigEndian: mixed-endian hosts are not supported");
constexpr const char* kByteOrder = std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";

template <typename T>
std::string_view bytes_of(const T* data, std::size_t count) {
  return {reinterpret_cast<const char*>(data), count * sizeof(T)};
}

void append_u64(std::string& out, std::uint64_t v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); }

// Compresses `bytes` in kZlibBlockSize blocks (in parallel: blocks are independent)
// and returns the header (see vtu_appended.hpp) and the blocks one after another.
std::pair<std::string, std::string> zlib_blocks(std::string_view bytes) {
  const std::uint64_t n = bytes.size();
  const std::int64_t nblocks = static_cast<std::int64_t>((n + kZlibBlockSize - 1) / kZlibBlockSize);
  std::vector<std::string> blocks(static_cast<std::size_t>(nblocks));
  bool failed = false;
#pragma omp parallel for schedule(dynamic, 8) reduction(|| : failed)
  for (std::int64_t b = 0; b < nblocks; ++b) {
    const std::uint64_t begin = static_cast<std::uint64_t>(b) * kZlibBlockSize;
    const uLong len = static_cast<uLong>(std::min(kZlibBlockSize, n - begin));
    std::string& out = blocks[static_cast<std::size_t>(b)];
    out.resize(compressBound(len));
    uLongf out_len = static_cast<uLongf>(out.size());
    // Level 5: vtkZLibDataCompressor's default CompressionLevel, ParaView's trade-off.
    if (compress2(reinterpret_cast<Bytef*>(out.data()), &out_len, reinterpret_cast<const Bytef*>(bytes.data() + begin),
                  len, 5) != Z_OK)
      failed = true;
    out.resize(out_len);
  }
  if (failed) throw std::runtime_error("zlib compress2 failed while writing a .vtu array");
  std::string header, data;
  append_u64(header, static_cast<std::uint64_t>(nblocks));
  append_u64(header, kZlibBlockSize);
  append_u64(header, n % kZlibBlockSize);
  std::size_t total = 0;
  for (const auto& b : blocks) {
    append_u64(header, b.size());
    total += b.size();
  }
  data.reserve(total);
  for (const auto& b : blocks) data += b;
  return {std::move(header), std::move(data)};
}

// One DataArray element referring to the appended block.
std::string data_array(std::string_view type, std::string_view name, Eigen::Index components, std::uint64_t offset) {
  std::string c = components > 0 ? fmt::format(" NumberOfComponents=\"{}\"", components) : "";
  return fmt::format("        <DataArray type=\"{}\" Name=\"{}\"{} format=\"appended\" offset=\"{}\"/>\n", type,
                     xml_escape(name), c, offset);
}

std::string field_block(AppendedData& appended, std::string_view tag, const std::vector<VtuField>& fields) {
  std::string xml = fmt::format("      <{}>\n", tag);
  for (const auto& f : fields) {
    // Eigen is column-major: column j (tuple j) is components contiguous, VTK's order.
    const auto offset = appended.add(bytes_of(f.values.data(), static_cast<std::size_t>(f.values.size())));
    xml += data_array("Float64", f.name, f.values.rows(), offset);
  }
  return xml + fmt::format("      </{}>\n", tag);
}

}  // namespace

std::uint64_t AppendedData::add(std::string_view bytes) {
  Entry e;
  if (compress_) {
    auto [header, data] = zlib_blocks(bytes);
    e.header = std::move(header);
    e.compressed = std::move(data);
  } else {
    append_u64(e.header, bytes.size());
    e.data = bytes;
  }
  const std::uint64_t offset = size_;
  size_ += e.header.size() + (compress_ ? e.compressed.size() : e.data.size());
  entries_.push_back(std::move(e));
  return offset;
}

void AppendedData::write_to(AtomicFile& file) const {
  file.write("  <AppendedData encoding=\"raw\">\n   _");
  for (const auto& e : entries_) {
    file.write(e.header);
    // One write per array: no per-value formatting or copying.
    file.write(compress_ ? std::string_view(e.compressed) : e.data);
  }
  file.write("\n  </AppendedData>\n");
}

void write_vtu_appended(const std::string& path, const Mesh& mesh, const std::vector<int>& perm, int vtk_type,
                        const std::vector<VtuField>& point_fields, const std::vector<VtuField>& cell_fields,
                        bool compress) {
  const Eigen::Index ncells = mesh.elements.cols();
  const int npe = static_cast<int>(mesh.elements.rows());
  std::vector<std::int64_t> connectivity(static_cast<std::size_t>(ncells * npe));
  std::vector<std::int64_t> offsets(static_cast<std::size_t>(ncells));
  const std::vector<std::uint8_t> types(static_cast<std::size_t>(ncells), static_cast<std::uint8_t>(vtk_type));
  for (Eigen::Index e = 0; e < ncells; ++e) {
    for (int k = 0; k < npe; ++k) connectivity[static_cast<std::size_t>(e * npe + k)] = mesh.elements(perm[k], e);
    offsets[static_cast<std::size_t>(e)] = (e + 1) * static_cast<std::int64_t>(npe);  // end offsets, no leading 0
  }

  AppendedData appended(compress);
  std::string xml = "<?xml version=\"1.0\"?>\n";
  // version 1.0: the first VTK XML version with header_type (vtkXMLWriter writes 1.0 for UInt64 headers).
  xml += fmt::format("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"{}\" header_type=\"UInt64\"{}>\n",
                     kByteOrder, compress ? " compressor=\"vtkZLibDataCompressor\"" : "");
  xml += "  <UnstructuredGrid>\n";
  xml += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", mesh.nodes.cols(), ncells);
  xml += field_block(appended, "PointData", point_fields);
  xml += field_block(appended, "CellData", cell_fields);
  xml += "      <Points>\n";
  xml += data_array("Float64", "Points", 3,
                    appended.add(bytes_of(mesh.nodes.data(), static_cast<std::size_t>(mesh.nodes.size()))));
  xml += "      </Points>\n      <Cells>\n";
  xml += data_array("Int64", "connectivity", 0, appended.add(bytes_of(connectivity.data(), connectivity.size())));
  xml += data_array("Int64", "offsets", 0, appended.add(bytes_of(offsets.data(), offsets.size())));
  xml += data_array("UInt8", "types", 0, appended.add(bytes_of(types.data(), types.size())));
  xml += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n";

  AtomicFile file(path);
  file.write(xml);
  appended.write_to(file);
  file.write("</VTKFile>\n");
  file.commit();
}

}  // namespace hofem::detail
