// The binary .vtu layouts (io/vtu_appended.hpp): offsets, UInt64 byte counts and
// zlib block headers read back byte by byte from files written for one Tet4 and
// compared with counts worked out by hand. (ctest vtu.meshio_roundtrip reads
// the same encodings back through meshio, decompression included.)
#include "io/vtu_writer.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

namespace hofem {
namespace {

// The reference tetrahedron as a one-element Tet4 mesh.
Mesh one_tet() {
  Mesh m;
  m.cell = CellType::Tetrahedron;
  m.order = 1;
  m.nodes.resize(3, 4);
  m.nodes << 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1;
  m.elements.resize(4, 1);
  m.elements << 0, 1, 2, 3;
  return m;
}

class VtuAppended : public ::testing::Test {
 protected:
  std::string path_ = (std::filesystem::temp_directory_path() /
                       ("hofem_vtu_appended_" + std::to_string(::getpid()) + ".vtu")).string();
  void TearDown() override { std::filesystem::remove(path_); }

  std::string read() const {
    std::ifstream in(path_, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
  }
  // The offset attributes in file order, and where the data after '_' starts.
  static std::vector<std::uint64_t> offsets(const std::string& text) {
    std::vector<std::uint64_t> r;
    const std::regex re("offset=\"([0-9]+)\"");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it)
      r.push_back(std::stoull((*it)[1]));
    return r;
  }
  static std::size_t data_start(const std::string& text) {
    const std::string tag = "<AppendedData encoding=\"raw\">";
    const std::size_t at = text.find(tag);
    EXPECT_NE(at, std::string::npos);
    const std::size_t underscore = text.find('_', at + tag.size());
    EXPECT_NE(underscore, std::string::npos);
    return underscore + 1;
  }
  static std::uint64_t u64(const std::string& text, std::size_t at) {
    std::uint64_t v = 0;
    std::memcpy(&v, text.data() + at, sizeof v);  // the test host is little-endian, as the file says
    return v;
  }
};

TEST_F(VtuAppended, RawArraysAreByteCountThenBytesAtTheirOffsets) {
  Eigen::MatrixXd u(3, 4);
  u << 0.1, -2.5e-300, 3, 1.0 / 3, 4, 5, 6, 7, 8, 9, 10, std::nextafter(1.0, 2.0);
  write_vtu(path_, one_tet(), {{"u", u}}, {{"c", Eigen::MatrixXd::Constant(1, 1, 2.5)}}, VtuFormat::binary);
  const std::string t = read();
  EXPECT_NE(t.find("header_type=\"UInt64\""), std::string::npos);
  EXPECT_NE(t.find("byte_order=\"LittleEndian\""), std::string::npos);
  EXPECT_EQ(t.find("compressor"), std::string::npos);
  // By hand, in file order: u 12 doubles (96 B), c 1 (8 B), Points 12 (96 B),
  // connectivity 4 Int64 (32 B), offsets 1 Int64 (8 B), types 1 UInt8 (1 B); each
  // preceded by an 8-byte count: 0, 8+96, +8+8, +8+96, +8+32, +8+8.
  const std::vector<std::uint64_t> expected_offsets{0, 104, 120, 224, 264, 280};
  const std::vector<std::uint64_t> expected_sizes{96, 8, 96, 32, 8, 1};
  ASSERT_EQ(offsets(t), expected_offsets);
  const std::size_t s = data_start(t);
  for (std::size_t i = 0; i < expected_sizes.size(); ++i)
    EXPECT_EQ(u64(t, s + expected_offsets[i]), expected_sizes[i]) << "array " << i;
  for (int k = 0; k < 12; ++k) {
    double v = 0;
    std::memcpy(&v, t.data() + s + 8 + 8 * k, 8);
    EXPECT_EQ(v, u(k % 3, k / 3)) << "u value " << k;  // bit for bit: no tolerance
  }
  for (int k = 0; k < 4; ++k) EXPECT_EQ(u64(t, s + 232 + 8 * k), static_cast<std::uint64_t>(k));
  EXPECT_EQ(u64(t, s + 272), 4u);                        // end offset of the one cell
  EXPECT_EQ(static_cast<unsigned char>(t[s + 288]), 10);  // VTK_TETRA
  EXPECT_EQ(t.substr(s + 289), "\n  </AppendedData>\n</VTKFile>\n");
}

// vtkZLibDataCompressor headers: blocks, block size (32768), the last block's size
// if partial (else 0), then each block's compressed size; the next array starts
// right after the compressed bytes.
TEST_F(VtuAppended, ZlibHeadersCountBlocksOfThe32KiBBlockSize) {
  // Point fields of 1024, 2048 and 1025 components on 4 nodes: 32768 B (one full
  // block), 65536 B (two full blocks), 32800 B (one full block and 32 B).
  const std::vector<VtuField> fields{{"a", Eigen::MatrixXd::Constant(1024, 4, 0.5)},
                                     {"b", Eigen::MatrixXd::Constant(2048, 4, 1.5)},
                                     {"c", Eigen::MatrixXd::Constant(1025, 4, 2.5)}};
  write_vtu(path_, one_tet(), fields, {}, VtuFormat::zlib);
  const std::string t = read();
  EXPECT_NE(t.find("compressor=\"vtkZLibDataCompressor\""), std::string::npos);
  const std::vector<std::uint64_t> off = offsets(t);
  ASSERT_EQ(off.size(), 7u);  // 3 fields, Points, connectivity, offsets, types
  const std::size_t s = data_start(t);
  const std::uint64_t blocks[3] = {1, 2, 2}, last[3] = {0, 0, 32};
  for (int i = 0; i < 3; ++i) {
    const std::size_t h = s + off[i];
    EXPECT_EQ(u64(t, h), blocks[i]) << "field " << i;
    EXPECT_EQ(u64(t, h + 8), 32768u) << "field " << i;
    EXPECT_EQ(u64(t, h + 16), last[i]) << "field " << i;
    std::uint64_t compressed = 0;
    for (std::uint64_t b = 0; b < blocks[i]; ++b) compressed += u64(t, h + 24 + 8 * b);
    EXPECT_EQ(off[i + 1], off[i] + 24 + 8 * blocks[i] + compressed) << "field " << i;
  }
  // types: 1 byte in one partial block of 1 byte.
  EXPECT_EQ(u64(t, s + off[6]), 1u);
  EXPECT_EQ(u64(t, s + off[6] + 16), 1u);
}

TEST(VtuFormatText, ParsesTheThreeNamesAndNamesABadOne) {
  EXPECT_EQ(parse_vtu_format("ascii"), VtuFormat::ascii);
  EXPECT_EQ(parse_vtu_format("binary"), VtuFormat::binary);
  EXPECT_EQ(parse_vtu_format("zlib"), VtuFormat::zlib);
  EXPECT_EQ(to_string(VtuFormat::zlib), "zlib");
  try {
    parse_vtu_format("gzip");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'gzip'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hofem
