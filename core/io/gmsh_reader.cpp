// Gmsh .msh reader, ASCII 4.1 and 2.2 (format: gmsh.info/doc/texinfo "MSH file format").
//
// Gmsh writes one record per line, so the text is read line by line and every record
// is checked against the number of values it must have; that is what lets each error
// name its line. Sections are first read into raw tables (nodes, elements, entities,
// names); assemble() then keeps the volume elements and the physical groups and
// renumbers the nodes that are used.
#include "io/gmsh_reader.hpp"
#include "io/input_file.hpp"
#include "io/text_lines.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <map>
#include <unordered_map>
#include <utility>
#include <vector>

namespace hofem {
namespace {

struct GmshType {
  int id, dim, num_nodes;
  const char* name;
};
// The element types hofem reads (numbers and node counts from Gmsh's GmshDefines.h).
constexpr GmshType kTypes[] = {{15, 0, 1, "Point"}, {1, 1, 2, "Line2"},  {8, 1, 3, "Line3"},   {26, 1, 4, "Line4"},
                               {2, 2, 3, "Tri3"},   {9, 2, 6, "Tri6"},   {21, 2, 10, "Tri10"}, {3, 2, 4, "Quad4"},
                               {16, 2, 8, "Quad8"}, {4, 3, 4, "Tet4"},   {11, 3, 10, "Tet10"}, {29, 3, 20, "Tet20"},
                               {5, 3, 8, "Hex8"},   {17, 3, 20, "Hex20"}};
// Gmsh volume types hofem does not read (prisms, pyramids, Hex27, Tet35/56, Hex64/125).
// A 2.2 element line carries no dimension, so this is how such a volume is recognised.
constexpr int kOtherVolumeTypes[] = {6, 7, 12, 13, 14, 18, 19, 30, 31, 92, 93};
constexpr const char* kSupported = "Tet4 (4), Tet10 (11), Tet20 (29), Hex8 (5), Hex20 (17)";

const GmshType* find_type(int id) {
  for (const auto& t : kTypes)
    if (t.id == id) return &t;
  return nullptr;
}

using detail::quoted;
using Lines = detail::TextLines;

using Key = std::pair<int, int>;  // (dimension, tag)

struct RawElement {
  long long tag;  // the element's number in the file
  int type;
  int dim;    // entity dimension (4.1), dimension of the type (2.2), -1 if unknown
  int group;  // 4.1: entity tag; 2.2: physical tag (0 = none)
  int line;
  std::size_t first;  // into Parser::element_nodes_: node tags, later node indices
  int count;
};

class Parser {
 public:
  Parser(std::string_view text, std::string_view origin) : in_(text, origin), origin_(origin) {}

  Mesh run() {
    read_format();
    while (in_.next()) {
      const std::string_view head = in_.tok(0);
      if (head[0] != '$' || in_.size() != 1)
        in_.fail(fmt::format("expected a section header such as $Nodes, got {}", quoted(in_.rest(0))));
      if (head.substr(0, 4) == "$End") in_.fail(fmt::format("{} without a matching opening section", quoted(head)));
      section_ = std::string(head.substr(1));
      section_line_ = in_.number();
      if (section_ == "MeshFormat") in_.fail("second $MeshFormat section");
      if (section_ == "PartitionedEntities")
        in_.fail("partitioned meshes ($PartitionedEntities) are not supported; save the mesh unpartitioned");
      if (section_ == "PhysicalNames")
        read_names();
      else if (section_ == "Entities" && v4_)
        read_entities();  // 2.2 has none: skipped
      else if (section_ == "Nodes")
        v4_ ? read_nodes4() : read_nodes2();
      else if (section_ == "Elements")
        v4_ ? read_elements4() : read_elements2();
      else
        skip_section();
    }
    return assemble();
  }

 private:
  [[noreturn]] void missing_end() const {
    in_.fail(
        fmt::format("file ends inside ${} (opened at line {}): $End{} missing", section_, section_line_, section_));
  }
  // Records the line of a section that may appear only once.
  void once(int& seen) {
    if (seen) in_.fail(fmt::format("second ${} section (the first is at line {})", section_, seen));
    seen = section_line_;
  }
  // A section whose first line is a single count (2.2 nodes and elements, names),
  // then that many records, each read by read_record.
  template <class ReadRecord>
  void read_counted(std::string_view count_what, std::string_view what, ReadRecord read_record) {
    record(count_what);
    in_.expect_size(1, count_what);
    const long long n = in_.integer(0, count_what, 0, INT_MAX);
    for (long long i = 0; i < n; ++i) {
      record(what);
      read_record();
    }
    end_section();
  }
  // A 4.1 $Nodes or $Elements section (once): numEntityBlocks numEntries minTag maxTag,
  // then the blocks; read_block reads one and returns how many `entries` it held.
  template <class ReadBlock>
  void read_blocks(int& seen_line, std::string_view entries, ReadBlock read_block) {
    once(seen_line);
    record(fmt::format("the numbers of blocks and {}", section_));
    in_.expect_size(4, fmt::format("numEntityBlocks num{} minTag maxTag", section_));
    const long long blocks = in_.integer(0, "number of blocks", 0, LLONG_MAX);
    const long long total = in_.integer(1, "total count", 0, INT_MAX);
    const int header = in_.number();
    long long seen = 0;
    for (long long b = 0; b < blocks; ++b)
      if ((seen += read_block()) > INT_MAX) in_.fail(fmt::format("too many {}", entries));
    if (seen != total)
      in_.fail_at(header, fmt::format("${} announces {} {} but its blocks hold {}", section_, total, entries, seen));
    end_section();
  }
  // An unknown section ($Comments, $NodeData, $Periodic, ...): skipped up to its end.
  void skip_section() {
    const std::string end = "$End" + section_;
    while (in_.next())
      if (in_.tok(0) == end) return;
    missing_end();
  }
  // Advances to the next record of the current section.
  void record(std::string_view what) {
    if (!in_.next()) missing_end();
    if (in_.tok(0)[0] == '$')
      in_.fail(fmt::format("truncated ${} section: expected {}, got {} (fewer entries than announced)", section_, what,
                           quoted(in_.tok(0))));
  }
  void end_section() {
    if (!in_.next()) missing_end();
    if (in_.size() != 1 || in_.tok(0) != "$End" + section_)
      in_.fail(fmt::format("expected $End{} after the announced entries, got {} (more entries than announced?)",
                           section_, quoted(in_.rest(0))));
  }

  void read_format() {
    if (!in_.next()) in_.fail("empty input: missing $MeshFormat");
    if (in_.tok(0) != "$MeshFormat")
      in_.fail(fmt::format("missing $MeshFormat: a Gmsh .msh file starts with it, got {}", quoted(in_.rest(0))));
    section_ = "MeshFormat";
    section_line_ = in_.number();
    record("version, file type and data size");
    in_.expect_size(3, "version file-type data-size");
    const double version = in_.real(0, "format version");
    v4_ = std::abs(version - 4.1) < 1e-9;
    if (!v4_ && std::abs(version - 2.2) > 1e-9)
      in_.fail(
          fmt::format("unsupported .msh format version {}; supported versions are 4.1 and 2.2 (ASCII)", in_.tok(0)));
    const int type = in_.small(1, "file type");
    if (type == 1) in_.fail("binary .msh files are not supported; only ASCII is supported (save with Mesh.Binary = 0)");
    if (type != 0) in_.fail(fmt::format("file type must be 0 (ASCII), got {}", type));
    in_.small(2, "data size");
    end_section();
  }

  void read_names() {
    read_counted("number of physical names", "a physical name", [&] {
      if (in_.size() < 3) in_.fail(fmt::format("expected 'dimension tag \"name\"', got {}", quoted(in_.rest(0))));
      const Key key{in_.small(0, "physical group dimension", 0, 3), in_.small(1, "physical tag")};
      std::string_view name = in_.rest(2);
      if (name.front() == '"') {
        if (name.size() < 2 || name.back() != '"') in_.fail(fmt::format("unterminated physical name {}", quoted(name)));
        name = name.substr(1, name.size() - 2);
      }
      if (name.empty()) in_.fail("empty physical name");
      if (!names_.emplace(key, std::string(name)).second)
        in_.fail(fmt::format("physical group (dimension {}, tag {}) is named twice", key.first, key.second));
    });
  }

  // 4.1: which physical groups each point, curve, surface and volume belongs to.
  void read_entities() {
    once(entities_line_);
    record("entity counts");
    in_.expect_size(4, "numPoints numCurves numSurfaces numVolumes");
    long long counts[4];
    for (int d = 0; d < 4; ++d) counts[d] = in_.integer(d, "number of entities", 0, LLONG_MAX);
    for (int d = 0; d < 4; ++d) {
      for (long long i = 0; i < counts[d]; ++i) {
        record(fmt::format("a dimension-{} entity", d));
        const std::size_t at = d == 0 ? 4 : 7;  // after tag and X Y Z (point) or the bounding box
        if (in_.size() < at + 1) in_.fail(fmt::format("too few values for a dimension-{} entity", d));
        const Key key{d, in_.small(0, "entity tag")};
        for (std::size_t j = 1; j < at; ++j) in_.real(j, "entity coordinate");
        const auto np = static_cast<std::size_t>(in_.integer(at, "number of physical tags", 0, in_.size() - at - 1));
        std::vector<int> physicals;
        for (std::size_t j = 0; j < np; ++j) physicals.push_back(in_.small(at + 1 + j, "physical tag"));
        const std::size_t nb_at = at + 1 + np;
        if (d == 0) {
          in_.expect_size(nb_at, "point entity");
        } else {
          if (in_.size() <= nb_at) in_.fail("missing the number of bounding entities");
          const long long nb = in_.integer(nb_at, "number of bounding entities", 0, in_.size() - nb_at - 1);
          in_.expect_size(nb_at + 1 + nb, "entity with its bounding entities");
          for (std::size_t j = nb_at + 1; j < in_.size(); ++j) in_.small(j, "bounding entity tag");
        }
        if (!entity_physicals_.emplace(key, std::move(physicals)).second)
          in_.fail(fmt::format("entity (dimension {}, tag {}) listed twice", d, key.second));
      }
    }
    end_section();
  }

  void add_node(long long tag) {
    if (static_cast<long long>(node_line_.size()) >= input_limits().nodes)
      in_.fail(fmt::format("more than {} nodes: over the cap (raise it with --limit nodes=N)", input_limits().nodes));
    const auto [it, inserted] = node_index_.emplace(tag, static_cast<int>(node_line_.size()));
    if (!inserted)
      in_.fail(fmt::format("duplicate node tag {} (first defined at line {})", tag, node_line_[it->second]));
    node_line_.push_back(in_.number());
  }
  void add_coordinates(std::size_t first) {
    for (std::size_t j = 0; j < 3; ++j) xyz_.push_back(in_.real(first + j, "node coordinate"));
  }

  void read_nodes4() {
    read_blocks(nodes_line_, "nodes", [&] {
      record("a node block header");
      in_.expect_size(4, "entityDim entityTag parametric numNodesInBlock");
      const int dim = in_.small(0, "entity dimension", 0, 3);
      in_.small(1, "entity tag");
      const int parametric = in_.small(2, "parametric flag", 0, 1);
      const long long n = in_.integer(3, "number of nodes in block", 0, INT_MAX);
      for (long long i = 0; i < n; ++i) {
        record("a node tag");
        in_.expect_size(1, "node tag");
        add_node(in_.integer(0, "node tag", 1, LLONG_MAX));
      }
      for (long long i = 0; i < n; ++i) {
        record("node coordinates");
        in_.expect_size(3 + parametric * dim, parametric ? "x y z and parametric coordinates" : "x y z");
        add_coordinates(0);
      }
      return n;
    });
  }

  void read_nodes2() {
    once(nodes_line_);
    read_counted("number of nodes", "a node", [&] {
      in_.expect_size(4, "node tag x y z");
      add_node(in_.integer(0, "node tag", 1, LLONG_MAX));
      add_coordinates(1);
    });
  }

  // Stores the element on the current line; its node tags are tokens first..end.
  void add_element(long long tag, int type, int dim, int group, std::size_t first) {
    // The cap is checked per record, so a count bomb in a header allocates nothing.
    if (static_cast<long long>(elements_.size()) >= input_limits().elements)
      in_.fail(fmt::format("more than {} elements: over the cap (raise it with --limit elements=N)",
                           input_limits().elements));
    const GmshType* t = find_type(type);
    const std::size_t listed = in_.size() - first;
    if (t && listed != static_cast<std::size_t>(t->num_nodes))
      in_.fail(fmt::format("a {} (element type {}) has {} nodes, but this element lists {}", t->name, type,
                           t->num_nodes, listed));
    if (!t && listed == 0) in_.fail(fmt::format("element of type {} lists no nodes", type));
    elements_.push_back({tag, type, dim, group, in_.number(), element_nodes_.size(), static_cast<int>(listed)});
    for (std::size_t j = first; j < in_.size(); ++j) element_nodes_.push_back(in_.integer(j, "node tag", 1, LLONG_MAX));
  }

  void read_elements4() {
    read_blocks(elements_line_, "elements", [&] {
      record("an element block header");
      in_.expect_size(4, "entityDim entityTag elementType numElementsInBlock");
      const int dim = in_.small(0, "entity dimension", 0, 3);
      const int entity = in_.small(1, "entity tag");
      const int type = in_.small(2, "element type");
      const long long n = in_.integer(3, "number of elements in block", 0, INT_MAX);
      const GmshType* t = find_type(type);
      if (t && t->dim != dim)
        in_.fail(fmt::format("element type {} ({}) is {}-dimensional but its block is on a {}-dimensional entity", type,
                             t->name, t->dim, dim));
      for (long long i = 0; i < n; ++i) {
        record("an element");
        add_element(in_.integer(0, "element tag", 1, LLONG_MAX), type, dim, entity, 1);
      }
      return n;
    });
  }

  void read_elements2() {
    once(elements_line_);
    read_counted("number of elements", "an element", [&] {
      if (in_.size() < 3) in_.fail("expected 'elm-number elm-type number-of-tags <tags> <nodes>'");
      const long long tag = in_.integer(0, "element number", 1, LLONG_MAX);
      const int type = in_.small(1, "element type");
      const auto ntags = static_cast<std::size_t>(in_.integer(2, "number of tags", 0, in_.size() - 3));
      for (std::size_t j = 0; j < ntags; ++j) in_.small(3 + j, "element tag");
      const GmshType* t = find_type(type);
      const bool other_volume =
          std::find(std::begin(kOtherVolumeTypes), std::end(kOtherVolumeTypes), type) != std::end(kOtherVolumeTypes);
      add_element(tag, type, t ? t->dim : (other_volume ? 3 : -1), ntags ? in_.small(3, "physical tag") : 0, 3 + ntags);
    });
  }

  Mesh assemble() {
    if (!nodes_line_) in_.fail("no $Nodes section");
    if (!elements_line_) in_.fail("no $Elements section");
    const GmshType* volume = nullptr;
    int volume_line = 0;
    std::vector<char> used(node_line_.size(), 0);
    std::vector<std::size_t> volumes;                // kept volume elements (indices into elements_)
    std::map<Key, std::vector<std::size_t>> groups;  // physical group -> its elements
    std::vector<int> physicals;
    for (std::size_t k = 0; k < elements_.size(); ++k) {
      const RawElement& e = elements_[k];
      physicals.clear();
      if (v4_) {
        const auto it = entity_physicals_.find({e.dim, e.group});
        if (it != entity_physicals_.end())
          physicals = it->second;
        else if (entities_line_)
          in_.fail_at(e.line,
                      fmt::format("the element's entity (dimension {}, tag {}) is not in $Entities", e.dim, e.group));
      } else if (e.group != 0) {
        physicals.push_back(e.group);
      }
      const GmshType* t = find_type(e.type);
      if (!t) {
        if (e.dim == 3 || !physicals.empty())
          in_.fail_at(e.line,
                      fmt::format("unsupported element type {} ({}); hofem reads the volume types {} and, for "
                                  "physical groups, points, lines, triangles and quads{}",
                                  e.type, e.dim == 3 ? "a volume element" : "in a physical group", kSupported,
                                  e.type == 10 || e.type == 12 ? " (Gmsh writes Quad8/Hex20 instead of "
                                                                 "Quad9/Hex27 with Mesh.SecondOrderIncomplete = 1)"
                                                               : ""));
        continue;
      }
      if (e.dim == 3) {
        if (!volume) {
          volume = t;
          volume_line = e.line;
        }
        if (volume != t)
          in_.fail_at(e.line, fmt::format("the mesh mixes volume element types: {} (type {}) here, {} (type {}) at "
                                          "line {}; a hofem mesh has one element type",
                                          t->name, t->id, volume->name, volume->id, volume_line));
        volumes.push_back(k);
      } else if (physicals.empty()) {
        continue;
      }
      for (int j = 0; j < e.count; ++j) {
        long long& node = element_nodes_[e.first + j];
        const auto it = node_index_.find(node);
        if (it == node_index_.end())
          in_.fail_at(e.line, fmt::format("the element references node tag {}, which is not defined in $Nodes", node));
        node = it->second;  // from here on: index in file order
        used[it->second] = 1;
      }
      for (const int p : physicals) groups[{e.dim, p}].push_back(k);
    }
    if (!volume)
      in_.fail_at(elements_line_,
                  fmt::format("no volume elements of a supported type ({}); note that when physical "
                              "groups exist Gmsh saves only their elements (Mesh.SaveAll = 1 saves all)",
                              kSupported));

    std::vector<int> id(used.size(), -1);
    int n = 0;
    for (std::size_t i = 0; i < used.size(); ++i)
      if (used[i]) id[i] = n++;
    Mesh mesh;
    const bool hex = volume->id == 5 || volume->id == 17;
    mesh.cell = hex ? CellType::Hexahedron : CellType::Tetrahedron;
    mesh.order = hex ? (volume->num_nodes == 8 ? 1 : 2)
                     : (volume->num_nodes == 4    ? 1
                        : volume->num_nodes == 10 ? 2
                                                  : 3);
    mesh.nodes.resize(3, n);
    for (std::size_t i = 0; i < used.size(); ++i)
      if (used[i]) mesh.nodes.col(id[i]) = Eigen::Vector3d(xyz_[3 * i], xyz_[3 * i + 1], xyz_[3 * i + 2]);
    mesh.elements.resize(volume->num_nodes, static_cast<Eigen::Index>(volumes.size()));
    mesh.source.file = origin_;
    std::vector<int> volume_index(elements_.size(), -1);
    for (std::size_t c = 0; c < volumes.size(); ++c) {
      const RawElement& e = elements_[volumes[c]];
      mesh.source.element_tags.push_back(e.tag);
      mesh.source.element_lines.push_back(e.line);
      volume_index[volumes[c]] = static_cast<int>(c);
      for (int j = 0; j < e.count; ++j)
        mesh.elements(j, static_cast<Eigen::Index>(c)) = id[element_nodes_[e.first + j]];
    }

    // Named groups without elements still give (empty) sets; unnamed ones are physical_<tag>.
    for (const auto& [key, name] : names_) {
      mesh.node_sets[name];
      if (key.first == 3) mesh.element_sets[name];
    }
    for (const auto& [key, members] : groups) {
      const auto named = names_.find(key);
      const std::string name = named != names_.end() ? named->second : fmt::format("physical_{}", key.second);
      std::vector<int>& nodes = mesh.node_sets[name];
      for (const std::size_t k : members) {
        const RawElement& e = elements_[k];
        for (int j = 0; j < e.count; ++j) nodes.push_back(id[element_nodes_[e.first + j]]);
        if (key.first == 3) mesh.element_sets[name].push_back(volume_index[k]);
      }
    }
    for (auto* sets : {&mesh.node_sets, &mesh.element_sets})
      for (auto& [name, set] : *sets) {
        std::sort(set.begin(), set.end());
        set.erase(std::unique(set.begin(), set.end()), set.end());
      }
    return mesh;
  }

  Lines in_;
  std::string origin_;
  bool v4_ = false;
  std::string section_;
  int section_line_ = 0, entities_line_ = 0, nodes_line_ = 0, elements_line_ = 0;
  std::map<Key, std::string> names_;
  std::map<Key, std::vector<int>> entity_physicals_;
  std::unordered_map<long long, int> node_index_;  // node tag -> index in file order
  std::vector<int> node_line_;                     // line of each node's tag
  std::vector<double> xyz_;                        // 3 per node, file order
  std::vector<RawElement> elements_;
  std::vector<long long> element_nodes_;
};

}  // namespace

Mesh read_gmsh_text(std::string_view text, std::string_view origin) { return Parser(text, origin).run(); }

Mesh read_gmsh(const std::string& path) {
  std::string text;
  try {
    text = read_input_file(path, "the mesh file", input_limits().mesh_file_bytes);
  } catch (const InputError& e) {
    throw MeshError(e.what());
  }
  return read_gmsh_text(text, path == "-" ? "<stdin>" : path);
}

}  // namespace hofem
