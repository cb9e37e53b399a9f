// Mesh file checks before assimp; see mesh_precheck.h.

#include "app/io/mesh_precheck.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <utility>
#include <sstream>
#include <string>
#include <vector>

#include "app/io/fbx_precheck.h"
#include "app/io/gltf_precheck.h"
#include "app/io/mesh_file.h"

namespace weft::app {

namespace {

// A PLY property: a scalar, or a list (count type, item type). Sizes in bytes; 0: unknown.
struct PlyProperty {
  std::string name;
  int size = 0;
  bool list = false;
  int count_size = 0;
  bool is_signed = false, count_signed = false, floating = false;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  bool ascii = false, big_endian = false;
  std::size_t body = 0;  // offset of the first byte after end_header
  std::vector<PlyElement> elements;
};

int ply_type_size(const std::string& t, bool& is_signed, bool& floating) {
  static const std::map<std::string, int> sizes = {
      {"char", -1}, {"int8", -1}, {"uchar", 1}, {"uint8", 1}, {"short", -2}, {"int16", -2},
      {"ushort", 2}, {"uint16", 2}, {"int", -4}, {"int32", -4}, {"uint", 4}, {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto it = sizes.find(t);
  if (it == sizes.end()) return 0;
  floating = t.rfind("float", 0) == 0 || t == "double";
  is_signed = it->second < 0 || floating;
  return it->second < 0 ? -it->second : it->second;
}

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw MeshFileError(name + ": " + what);
}

// "property TYPE NAME" or "property list COUNT_TYPE ITEM_TYPE NAME" (the words after "property").
PlyProperty read_ply_property(const std::vector<std::string>& w, const std::string& line,
                              const std::string& name) {
  PlyProperty p;
  bool count_floating = false;
  p.list = w.size() == 5 && w[1] == "list";
  if (w.size() != (p.list ? 5u : 3u)) fail(name, "PLY header line '" + line + "': malformed property");
  p.size = ply_type_size(p.list ? w[3] : w[1], p.is_signed, p.floating);
  if (p.list) p.count_size = ply_type_size(w[2], p.count_signed, count_floating);
  p.name = w.back();
  if (p.size == 0 || (p.list && (p.count_size == 0 || count_floating)))
    fail(name, "PLY header line '" + line + "': unknown or unusable type");
  return p;
}

// An element's name once in a header, and faces as `face` or `tristrips`, not both: assimp sizes
// its vertices (faces) by the first such element and writes the next one's past them (heap
// corruption, `free(): invalid next size` in the Release build; found by fuzzing).
bool assimp_reads_ply_element(const std::string& element) {
  return element == "vertex" || element == "face" || element == "tristrips" || element == "edge" ||
         element == "material";
}

// assimp reads the count of an element of another name from the start of its name (its parser
// does not skip the name): `element camera 1` has no items to it, `element 8888…8face 2` some
// 4·10⁹ (out-of-memory; found by fuzzing), and either misreads the elements after it. Such an
// element is refused before one assimp reads, or when its name starts with a digit, and not
// walked (weft's walk then reads what assimp reads).
void check_ply_element_name(const PlyHeader& h, const std::string& element, std::size_t line,
                            const std::string& name) {
  const std::string where = "PLY header line " + std::to_string(line) + ": element '" + element + "'";
  if (element == "TextureFile" || std::isdigit(static_cast<unsigned char>(element[0])))
    fail(name, where + " (assimp reads a count from an element name starting with a digit)");
  if (assimp_reads_ply_element(element))
    for (const PlyElement& e : h.elements)
      if (!assimp_reads_ply_element(e.name))
        fail(name, where + " after element '" + e.name + "', which assimp takes as empty (it "
                           "reads vertex, face, tristrips, edge and material elements) and would "
                           "read its data as the next one's");
  for (const PlyElement& e : h.elements) {
    if (e.name == element)
      fail(name, where + " a second time (assimp would read it into the first one's arrays)");
    if ((e.name == "face" && element == "tristrips") || (e.name == "tristrips" && element == "face"))
      fail(name, where + " beside '" + e.name + "' (assimp would read both into one array of faces)");
  }
}

// The header, line by line: "ply", then only format, comment, obj_info, element and property
// lines up to an "end_header" line. Anything else is refused: assimp's reader was seen to hang
// on a misspelt keyword.
PlyHeader read_ply_header(std::string_view bytes, const std::string& name) {
  PlyHeader h;
  bool format = false;
  for (std::size_t at = 0, number = 1; at < bytes.size() && at < 65536; ++number) {
    const std::size_t end = std::min(bytes.find('\n', at), bytes.size());
    std::string line(bytes.substr(at, end - at));
    if (!line.empty() && line.back() == '\r') line.pop_back();
    at = end + 1;
    // A header is text: assimp leaks on an element name with a NUL in it (found by fuzzing).
    for (const char c : line)
      if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f)
        fail(name, "PLY header line " + std::to_string(number) + ": a control character (a PLY "
                   "header is text)");
    std::istringstream words_in(line);
    std::vector<std::string> w;
    for (std::string word; words_in >> word;) w.push_back(word);
    const std::string key = w.empty() ? "" : w[0];
    if (number == 1) {
      if (line != "ply") fail(name, "not a PLY file (expected its first line to be \"ply\")");
    } else if (key == "end_header" && w.size() == 1) {
      if (!format) fail(name, "the PLY header has no format line");
      // Without it assimp's reader was seen to loop (found by fuzzing; a 192-byte header).
      if (end == bytes.size()) fail(name, "the PLY header's end_header line has no line end");
      h.body = std::min(at, bytes.size());
      return h;
    } else if (key == "format" && w.size() == 3 && !format) {
      if (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian")
        fail(name, "PLY format '" + w[1] + "' (expected ascii or binary_*_endian)");
      h.ascii = w[1] == "ascii";
      h.big_endian = w[1] == "binary_big_endian";
      format = true;
    } else if (key == "element" && w.size() == 3) {
      if (w[2].find_first_not_of("0123456789") != std::string::npos || w[2].size() > 19)
        fail(name, "PLY element '" + w[1] + "': count '" + w[2] + "' (expected a whole number)");
      check_ply_element_name(h, w[1], number, name);
      // assimp counts an element of another name by the digits its name starts with (none: 0).
      h.elements.push_back({w[1], assimp_reads_ply_element(w[1]) ? std::stoull(w[2]) : 0, {}});
    } else if (key == "property" && !h.elements.empty()) {
      h.elements.back().properties.push_back(read_ply_property(w, line, name));
    } else if (key != "comment" && key != "obj_info") {
      fail(name, "PLY header line " + std::to_string(number) + ": '" + line +
                     "' (expected format, comment, obj_info, element, property or end_header)");
    }
  }
  fail(name, "not a PLY file (no \"end_header\" line in its first 64 KiB)");
}

// A value as the file gives it: 512, -1, 1.5, 1e+30.
std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// The index lists of faces: "vertex_indices" or "vertex_index" of the element "face".
bool is_face_list(const PlyElement& e, const PlyProperty& p) {
  return e.name == "face" && p.list && (p.name == "vertex_indices" || p.name == "vertex_index");
}

// A face's texture coordinates (two a corner), which assimp reads beside its last index list.
bool is_face_texcoords(const PlyElement& e, const PlyProperty& p) {
  return e.name == "face" && p.list && p.name == "texcoord";
}

// The body of a PLY file, read value by value with every read checked against its end. A text
// body is read as assimp reads it, one line for each element (its words parsed from that line
// alone): a body that is not plain text lines (a NUL, a form feed or a lone carriage return end
// a line there, and an empty line is skipped or read depending on what precedes it), or a word
// that is not a number of its property's type (assimp stops inside it and reads the rest as the
// next value), would make assimp read other numbers than these. A NUL in a face's line made
// assimp read a list count of 954 437 119 (15 GB, 57 s in the Release build; found by fuzzing).
class PlyBody {
 public:
  PlyBody(std::string_view bytes, const PlyHeader& h, const std::string& name)
      : m_bytes(bytes), m_at(h.body), m_next_line(h.body), m_ascii(h.ascii),
        m_big_endian(h.big_endian), m_name(name) {
    if (!m_ascii) return;
    for (std::size_t k = h.body; k < bytes.size(); ++k) {
      const auto c = static_cast<unsigned char>(bytes[k]);
      if ((c < 0x20 && c != '\t' && c != '\n' && !(c == '\r' && k + 1 < bytes.size() &&
                                                  bytes[k + 1] == '\n')) || c == 0x7f)
        fail(m_name, "PLY body byte " + std::to_string(k) + ": a control character (the body of "
                     "an ASCII PLY is lines of text)");
    }
  }

  // An element starts: a text body's next line (a binary body reads on).
  void start(const std::string& where) {
    if (!m_ascii) return;
    if (m_next_line >= m_bytes.size())
      fail(m_name, where + ": the file ends before it (truncated, or a bogus count)");
    const std::size_t end = std::min(m_bytes.find('\n', m_next_line), m_bytes.size());
    m_at = m_next_line;
    m_end = end > m_at && m_bytes[end - 1] == '\r' ? end - 1 : end;
    m_next_line = end + 1;
    if (m_at == m_end) fail(m_name, where + ": an empty line (expected the element's numbers)");
  }

  // An element ends: nothing more on its line.
  void finish(const std::string& where) {
    if (m_ascii && skip_spaces() < m_end)
      fail(m_name, where + ": more numbers on its line than the element's properties");
  }

  // The next value as a double (binary integers are exact up to 2⁵³, beyond any limit here).
  double next(int size, bool is_signed, bool floating, const std::string& where) {
    return m_ascii ? next_word(is_signed, floating, where)
                   : next_binary(size, is_signed, floating, where);
  }

 private:
  std::size_t skip_spaces() {
    while (m_at < m_end && (m_bytes[m_at] == ' ' || m_bytes[m_at] == '\t')) ++m_at;
    return m_at;
  }

  // A word of the line: digits (after a '-' for a signed type), for a floating type also a '.'
  // and an exponent; what assimp's readers of the type read whole.
  double next_word(bool is_signed, bool floating, const std::string& where) {
    const std::size_t start = skip_spaces();
    while (m_at < m_end && m_bytes[m_at] != ' ' && m_bytes[m_at] != '\t') ++m_at;
    if (start == m_at) fail(m_name, where + ": its line ends before it");
    const std::string word(m_bytes.substr(start, m_at - start));
    std::size_t k = word[0] == '-' && (is_signed || floating) ? 1 : 0, digits = 0;
    for (; k < word.size() && std::isdigit(static_cast<unsigned char>(word[k])); ++k) ++digits;
    if (floating && k < word.size() && word[k] == '.')
      for (++k; k < word.size() && std::isdigit(static_cast<unsigned char>(word[k])); ++k) ++digits;
    if (floating && digits > 0 && k < word.size() && (word[k] == 'e' || word[k] == 'E')) {
      k += k + 1 < word.size() && (word[k + 1] == '-' || word[k + 1] == '+') ? 2 : 1;
      const std::size_t exponent = k;
      while (k < word.size() && std::isdigit(static_cast<unsigned char>(word[k]))) ++k;
      if (k == exponent) digits = 0;
    }
    if (digits == 0 || k != word.size())
      fail(m_name, where + ": '" + word + "' is not " +
                       (floating ? "a number" : is_signed ? "an integer" : "a whole number"));
    return std::strtod(word.c_str(), nullptr);
  }

  double next_binary(int size, bool is_signed, bool floating, const std::string& where) {
    if (m_bytes.size() - m_at < static_cast<std::size_t>(size))
      fail(m_name, where + ": the file ends before it (truncated, or a bogus count)");
    unsigned char raw[8] = {};
    for (int k = 0; k < size; ++k)
      raw[m_big_endian ? size - 1 - k : k] = static_cast<unsigned char>(m_bytes[m_at + k]);
    m_at += static_cast<std::size_t>(size);
    std::uint64_t bits = 0;
    for (int k = size; k-- > 0;) bits = bits << 8 | raw[k];
    if (floating) return 0.0;  // positions: assimp reads them; non-finite ones are refused later
    if (is_signed && size < 8 && (bits >> (8 * size - 1)) & 1) bits |= ~std::uint64_t{0} << (8 * size);
    return is_signed ? static_cast<double>(static_cast<std::int64_t>(bits)) : static_cast<double>(bits);
  }

  std::string_view m_bytes;
  std::size_t m_at, m_end = 0, m_next_line;  // text: the line read, [m_at, m_end), and the next
  bool m_ascii, m_big_endian;
  const std::string& m_name;
};

// Elements over the limits, or more than the bytes after the header can hold.
void check_ply_counts(const PlyHeader& h, std::size_t body_bytes, const std::string& name) {
  for (const PlyElement& e : h.elements) {
    if ((e.name == "vertex" || e.name == "face") && e.count > max_mesh_elements)
      fail(name, "the PLY header says " + std::to_string(e.count) + " " + e.name + "s, more than " +
                     std::to_string(max_mesh_elements) + " (the limit of weft's mesh files)");
    std::uint64_t least = 0;  // bytes per element: one per list count, each scalar's size
    for (const PlyProperty& p : e.properties) least += h.ascii ? 2 : (p.list ? p.count_size : p.size);
    if (least > 0 && e.count > body_bytes / least)
      fail(name, "the PLY header says " + std::to_string(e.count) + " " + e.name +
                     " elements, more than its " + std::to_string(body_bytes) +
                     " bytes after the header can hold (truncated, or a bogus count)");
  }
}

// Walks every element; each face's corners must be vertices of the file, its texture
// coordinates at most two a corner.
void check_ply_body(std::string_view bytes, const PlyHeader& h, const std::string& name) {
  std::uint64_t vertices = 0;
  for (const PlyElement& e : h.elements)
    if (e.name == "vertex") vertices = e.count;
  PlyBody body(bytes, h, name);
  for (const PlyElement& e : h.elements)
    // A binary element without properties takes no bytes, whatever its count (up to 10¹⁹); a
    // text one a line.
    for (std::uint64_t i = 0; i < e.count && (h.ascii || !e.properties.empty()); ++i) {
      int corners = -1, texcoords = -1;  // the lists' lengths, as assimp takes them: the last
      body.start(e.name + " " + std::to_string(i));
      for (const PlyProperty& p : e.properties) {
        const std::string where = e.name + " " + std::to_string(i) + ", " + p.name;
        if (!p.list) {
          body.next(p.size, p.is_signed, p.floating, where);
          continue;
        }
        const double n = body.next(p.count_size, p.count_signed, false, where + "'s count");
        if (!(n >= 0 && n <= 255 && n == static_cast<double>(static_cast<int>(n))))
          fail(name, where + ": a list of " + number_text(n) + " items (expected 0 to 255)");
        if (is_face_list(e, p)) corners = static_cast<int>(n);
        if (is_face_texcoords(e, p)) texcoords = static_cast<int>(n);
        for (int k = 0; k < static_cast<int>(n); ++k) {
          const double v = body.next(p.size, p.is_signed, p.floating, where);
          if (is_face_list(e, p) && !(v >= 0 && v < static_cast<double>(vertices) &&
                                      v == static_cast<double>(static_cast<std::int64_t>(v))))
            fail(name, where + ": corner " + std::to_string(k) + " is vertex " + number_text(v) +
                           ", not one of the file's " + std::to_string(vertices) + " vertices");
        }
      }
      if (!e.properties.empty()) body.finish(e.name + " " + std::to_string(i));
      // assimp reads texture coordinate k at corner k / 2: past a face's corners (an invalid
      // read), or without corners through a null pointer (SIGSEGV in the Release build).
      if (texcoords > 2 * std::max(corners, 0))
        fail(name, e.name + " " + std::to_string(i) + ", texcoord: " + std::to_string(texcoords) +
                       " texture coordinates for " + std::to_string(std::max(corners, 0)) +
                       " corners (at most two a corner)");
    }
}

// An OBJ line's numbers from the `first`-th on (0-based, after the keyword) must be finite as
// floats: assimp reads `vt nan 0` and `vt 1e39 0` as `vt 0 0`, silently, and so a colour or a
// normal. (A vertex's position, its first three numbers, is checked after the import, for every
// format.)
void check_obj_numbers(std::string_view line, std::uint64_t number, const std::string& name,
                       const char* what, int first) {
  const std::string text(line);
  const char* at = text.c_str() + text.find_first_of(" \t");
  for (int k = 0;; ++k) {
    while (*at == ' ' || *at == '\t' || *at == '\r') ++at;
    if (*at == '\0' || *at == '#') return;  // the line's end, or a comment
    const char* word = at;
    while (*at != '\0' && *at != ' ' && *at != '\t' && *at != '\r') ++at;
    if (k < first) continue;
    char* end = nullptr;
    const double v = std::strtod(word, &end);
    if (end != at || !std::isfinite(v) || std::fabs(v) > std::numeric_limits<float>::max())
      fail(name, "line " + std::to_string(number) + ": " + what + " '" + text + "': '" +
                     std::string(word, at) + "' is not a finite number (as a float)");
  }
}

// Counts an OBJ's vertex ("v ") and face ("f ") lines against the limit, and checks the numbers
// of its texture coordinate ("vt "), normal ("vn ") lines and vertex colours ("v x y z r g b").
void check_obj_counts(std::string_view bytes, const std::string& name) {
  std::uint64_t v = 0, f = 0, number = 0;
  for (std::size_t at = 0; at < bytes.size();) {
    const std::size_t end = std::min(bytes.find('\n', at), bytes.size());
    const std::string_view line = bytes.substr(at, end - at);
    ++number;
    if (line.size() > 1 && (line[1] == ' ' || line[1] == '\t')) {
      v += line[0] == 'v';
      f += line[0] == 'f';
    }
    const auto keyword = [&](std::string_view word) {
      return line.size() > word.size() && line.substr(0, word.size()) == word &&
             (line[word.size()] == ' ' || line[word.size()] == '\t');
    };
    if (keyword("vt")) check_obj_numbers(line, number, name, "texture coordinates", 0);
    if (keyword("vn")) check_obj_numbers(line, number, name, "normal", 0);
    if (keyword("v")) check_obj_numbers(line, number, name, "vertex colour", 3);
    at = end + 1;
  }
  for (const auto& [count, what] : {std::pair{v, "vertices"}, std::pair{f, "faces"}})
    if (count > max_mesh_elements)
      fail(name, "an OBJ of " + std::to_string(count) + " " + what + ", more than " +
                     std::to_string(max_mesh_elements) + " (the limit of weft's mesh files)");
}

// The little-endian uint32 at `at` (the caller checked that 4 bytes are there).
std::uint32_t glb_word(std::string_view bytes, std::size_t at) {
  std::uint32_t w = 0;
  for (int k = 3; k >= 0; --k) w = w << 8 | static_cast<unsigned char>(bytes[at + k]);
  return w;
}

// A GLB's header and chunk headers (glTF 2.0, "Binary glTF Layout"): assimp allocates a chunk's
// declared length before it reads the chunk, so a JSON chunk said to be 2 GB in an 878-byte file
// took 2 GB and 10 s before failing (found by fuzzing). Every length must fit in the file.
// Returns the JSON chunk (the first, glTF 2), or nothing for glTF 1's layout.
std::string_view check_glb(std::string_view bytes, const std::string& name) {
  if (bytes.size() < 12 || bytes.substr(0, 4) != "glTF")
    fail(name, "not a GLB file (it must start with the 12-byte header \"glTF\", version, length)");
  const std::uint32_t version = glb_word(bytes, 4), length = glb_word(bytes, 8);
  if (length > bytes.size())
    fail(name, "the GLB header says " + std::to_string(length) + " bytes, but the file holds " +
                   std::to_string(bytes.size()) + " (truncated, or a bogus length)");
  if (version != 2) return {};  // glTF 1's binary layout: one content length, checked by assimp
  std::string_view json;
  int chunk = 0;
  for (std::size_t at = 12; at < length; ++chunk) {
    if (length - at < 8)
      fail(name, "GLB chunk " + std::to_string(chunk) + ": its 8-byte header runs past the end");
    const std::uint32_t chunk_length = glb_word(bytes, at);
    if (chunk_length > length - at - 8)
      fail(name, "GLB chunk " + std::to_string(chunk) + " says " + std::to_string(chunk_length) +
                     " bytes, but the file holds " + std::to_string(length - at - 8) +
                     " after its header (truncated, or a bogus length)");
    if (chunk == 0 && glb_word(bytes, at + 4) == 0x4E4F534Au)  // "JSON"
      json = bytes.substr(at + 8, chunk_length);
    at += 8 + std::size_t{chunk_length};
  }
  return json;
}

}  // namespace

void precheck_mesh_bytes(std::string_view bytes, const std::string& extension,
                         const std::string& name) {
  if (extension == ".obj") check_obj_counts(bytes, name);
  if (extension == ".glb") check_gltf_json(check_glb(bytes, name), name);
  if (extension == ".gltf") check_gltf_json(bytes, name);
  if (extension == ".fbx") check_fbx(bytes, name);
  if (extension != ".ply") return;
  const PlyHeader h = read_ply_header(bytes, name);
  check_ply_counts(h, bytes.size() - h.body, name);
  check_ply_body(bytes, h, name);
}

}  // namespace weft::app
