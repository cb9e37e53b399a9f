// FBX scopes and model hierarchy before assimp; see fbx_precheck.h.

#include "app/io/fbx_precheck.h"

#include <algorithm>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "app/io/mesh_file.h"

namespace weft::app {

namespace {

enum class FbxTokenType { key, data, open, close, comma };

// A token's bytes [begin, end) of the file (a binary data token: its type code, then its value)
// and where it is: the line (text) or byte offset (binary), for messages.
struct FbxToken {
  FbxTokenType type;
  std::uint64_t begin, end, where;
};

// The file's bytes as assimp's FBX reader holds them: followed by one NUL.
class FbxBytes {
 public:
  explicit FbxBytes(std::string_view bytes) : m_bytes(bytes) {}
  std::uint64_t size() const { return m_bytes.size() + 1; }
  char at(std::uint64_t k) const { return k < m_bytes.size() ? m_bytes[k] : '\0'; }
  std::string piece(std::uint64_t begin, std::uint64_t end) const {
    std::string s;
    for (std::uint64_t k = begin; k < end; ++k) s += at(k);
    return s;
  }
  std::string_view view() const { return m_bytes; }

 private:
  std::string_view m_bytes;
};

// Tokens one at a time (the parser below asks for the next), so that a file of millions of
// numbers is never held as tokens.
class FbxTokenizer {
 public:
  virtual ~FbxTokenizer() = default;
  std::optional<FbxToken> next() {
    while (m_queue.empty() && step()) {
    }
    if (m_queue.empty()) return std::nullopt;
    const FbxToken t = m_queue.front();
    m_queue.pop_front();
    return t;
  }
  virtual std::string where(std::uint64_t at) const = 0;  // "line 3" or "byte 120"

 protected:
  // Reads on until it has queued a token; false at the end of the tokens.
  virtual bool step() = 0;
  void push(FbxTokenType type, std::uint64_t begin, std::uint64_t end, std::uint64_t where) {
    m_queue.push_back({type, begin, end, where});
  }

 private:
  std::deque<FbxToken> m_queue;
};

// Text: assimp's Tokenize (FBXTokenizer.cpp) character by character, its quirks kept (a NUL
// ends the text; `:` after a space, or `,` right after a bracket, is an error; a token left open
// at the end of the text is dropped).
class FbxTextTokenizer : public FbxTokenizer {
 public:
  FbxTextTokenizer(std::string_view bytes, std::string name)
      : m_text(bytes.substr(0, bytes.find('\0'))), m_name(std::move(name)) {}
  std::string where(std::uint64_t at) const override { return "line " + std::to_string(at); }

 protected:
  bool step() override {
    if (m_k >= m_text.size()) return false;
    const char c = m_text[m_k];
    if (c == '\r' || c == '\n' || c == '\f') {
      m_comment = false;
      ++m_line;
    }
    if (!m_comment) read(c);
    ++m_k;
    return true;
  }

 private:
  static bool space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f'; }

  void read(char c) {
    if (m_quoted) {
      if (c == '"') {
        m_quoted = false;
        m_end = m_k;
        flush(FbxTokenType::data, false);
        m_pending = false;
      }
      return;
    }
    switch (c) {
      case '"':
        if (m_begin) fail("unexpected double-quote");
        m_begin = m_k;
        m_quoted = true;
        return;
      case ';':
        flush(FbxTokenType::data, false);
        m_comment = true;
        return;
      case '{':
      case '}':
        flush(FbxTokenType::data, false);
        push(c == '{' ? FbxTokenType::open : FbxTokenType::close, m_k, m_k + 1, m_line);
        return;
      case ',':
        if (m_pending) flush(FbxTokenType::data, true);
        push(FbxTokenType::comma, m_k, m_k + 1, m_line);
        return;
      case ':':
        if (!m_pending) fail("unexpected colon");
        flush(FbxTokenType::key, true);
        return;
      default:
        break;
    }
    if (space(c)) {
      if (m_begin) flush(FbxTokenType::data, false);
      m_pending = false;
    } else {
      m_end = m_k;
      if (!m_begin) m_begin = m_k;
      m_pending = true;
    }
  }

  // assimp's ProcessDataToken: the token [m_begin, m_end] if there is one.
  void flush(FbxTokenType type, bool must_have_token) {
    if (m_begin && m_end) {
      bool quoted = false;
      for (std::uint64_t k = *m_begin; k <= *m_end; ++k) {
        if (m_text[k] == '"') quoted = !quoted;
        if (!quoted && space(m_text[k])) fail("unexpected whitespace in token");
      }
      if (quoted) fail("non-terminated double quotes");
      push(type, *m_begin, *m_end + 1, m_line);
    } else if (must_have_token) {
      fail("unexpected character, expected data token");
    }
    m_begin.reset();
    m_end.reset();
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw MeshFileError(m_name + ": FBX text weft cannot read: line " + std::to_string(m_line) +
                        ": " + what);
  }

  std::string_view m_text;
  std::string m_name;
  std::uint64_t m_k = 0, m_line = 1;
  bool m_comment = false, m_quoted = false, m_pending = false;
  std::optional<std::uint64_t> m_begin, m_end;
};

// Binary: assimp's TokenizeBinary (FBXBinaryTokenizer.cpp) node by node, with a stack of the
// open nodes' end offsets where assimp recurses: a node (end offset, property count and length,
// name) gives a key, its properties data tokens, its nested nodes a scope, closed by a NUL record.
class FbxBinaryTokenizer : public FbxTokenizer {
 public:
  FbxBinaryTokenizer(std::string_view bytes, std::string name)
      : m_bytes(bytes), m_name(std::move(name)) {
    if (m_bytes.size() < 0x1b) fail("file is too short");
    m_cursor = 23;  // the magic, 5 bytes
    m_long = read_word(m_bytes.size()) >= 7500;
  }
  std::string where(std::uint64_t at) const override { return "byte " + std::to_string(at); }

 protected:
  bool step() override {
    if (m_done) return false;
    if (!m_open.empty() && m_cursor >= m_open.back() - sentinel()) {
      close_node();
      return true;
    }
    if (m_open.empty() && m_cursor >= m_bytes.size()) return false;
    read_node(m_open.empty() ? m_bytes.size() : m_open.back() - sentinel());
    return true;
  }

 private:
  std::uint64_t sentinel() const { return m_long ? 25 : 13; }

  void read_node(std::uint64_t limit) {
    const std::uint64_t end = m_long ? read_long(limit) : read_word(limit);
    if (end == 0) {  // a NUL record: the end of the file's nodes, or nothing in a nested list
      m_done = m_open.empty();
      return;
    }
    if (end > limit) fail("block offset is out of range");
    if (end < m_cursor) fail("block offset is negative out of range");
    const std::uint64_t count = m_long ? read_long(limit) : read_word(limit);
    const std::uint64_t length = m_long ? read_long(limit) : read_word(limit);
    const auto [key_begin, key_end] = read_string(limit, false, false);
    push(FbxTokenType::key, key_begin, key_end, m_cursor);
    const std::uint64_t begin = m_cursor;
    if (length > limit - begin) fail("property length out of bounds reading length");
    for (std::uint64_t i = 0; i < count; ++i) {
      read_property(begin + length);
      if (i != count - 1) push(FbxTokenType::comma, m_cursor, m_cursor + 1, m_cursor);
    }
    if (m_cursor - begin != length) fail("property length not reached, something is wrong");
    if (m_cursor < end) {
      if (end - m_cursor < sentinel()) fail("insufficient padding bytes at block end");
      push(FbxTokenType::open, m_cursor, m_cursor + 1, m_cursor);
      m_open.push_back(end);
    } else if (m_cursor != end) {
      fail("scope length not reached, something is wrong");
    }
  }

  void close_node() {
    push(FbxTokenType::close, m_cursor, m_cursor + 1, m_cursor);
    for (std::uint64_t i = 0; i < sentinel(); ++i)
      if (m_bytes.at(m_cursor + i) != '\0')
        fail("failed to read nested block sentinel, expected all bytes to be 0");
    m_cursor += sentinel();
    if (m_cursor != m_open.back()) fail("scope length not reached, something is wrong");
    m_open.pop_back();
  }

  void read_property(std::uint64_t limit) {
    if (m_cursor >= limit) fail("cannot ReadData, out of bounds reading length");
    const std::uint64_t begin = m_cursor;
    const char type = m_bytes.at(m_cursor++);
    switch (type) {
      case 'Y':
        m_cursor += 2;
        break;
      case 'C':
        m_cursor += 1;
        break;
      case 'I':
      case 'F':
        m_cursor += 4;
        break;
      case 'D':
      case 'L':
        m_cursor += 8;
        break;
      case 'R': {
        const std::uint32_t length = read_word(limit);
        m_cursor += length;
        break;
      }
      case 'b':
        m_cursor = limit;
        break;
      case 'f':
      case 'd':
      case 'l':
      case 'i':
      case 'c':
        read_array(type, limit);
        break;
      case 'S':
        read_string(limit, true, true);
        break;
      default:
        fail(std::string("cannot ReadData, unexpected type code: ") + type);
    }
    if (m_cursor > limit)
      fail(std::string("cannot ReadData, the remaining size is too small for the data type: ") +
           type);
    push(FbxTokenType::data, begin, m_cursor, m_cursor);
  }

  void read_array(char type, std::uint64_t limit) {
    const std::uint32_t length = read_word(limit), encoding = read_word(limit),
                        compressed = read_word(limit);
    if (encoding == 0) {
      const std::uint32_t stride = (type == 'd' || type == 'l') ? 8 : type == 'c' ? 1 : 4;
      if (static_cast<std::uint32_t>(length * stride) != compressed)  // 32 bits, as assimp's
        fail("cannot ReadData, calculated data stride differs from what the file claims");
    } else if (encoding != 1) {
      fail("cannot ReadData, unknown encoding");
    }
    m_cursor += compressed;
  }

  std::pair<std::uint64_t, std::uint64_t> read_string(std::uint64_t limit, bool long_length,
                                                      bool allow_nul) {
    if (limit - m_cursor < (long_length ? 4u : 1u))
      fail("cannot ReadString, out of bounds reading length");
    const std::uint64_t length =
        long_length ? read_word(limit) : static_cast<unsigned char>(m_bytes.at(m_cursor++));
    if (limit - m_cursor < length) fail("cannot ReadString, length is out of bounds");
    const std::uint64_t begin = m_cursor;
    m_cursor += length;
    if (!allow_nul)
      for (std::uint64_t k = begin; k < m_cursor; ++k)
        if (m_bytes.at(k) == '\0') fail("failed ReadString, unexpected NUL character in string");
    return {begin, m_cursor};
  }

  std::uint64_t read_le(std::uint64_t limit, int size) {
    if (m_cursor > limit || limit - m_cursor < static_cast<std::uint64_t>(size))
      fail(size == 4 ? "cannot ReadWord, out of bounds" : "cannot ReadDoubleWord, out of bounds");
    std::uint64_t v = 0;
    for (int k = 0; k < size; ++k)
      v |= std::uint64_t{static_cast<unsigned char>(m_bytes.at(m_cursor + k))} << (8 * k);
    m_cursor += size;
    return v;
  }
  std::uint32_t read_word(std::uint64_t limit) {
    return static_cast<std::uint32_t>(read_le(limit, 4));
  }
  std::uint64_t read_long(std::uint64_t limit) { return read_le(limit, 8); }

  [[noreturn]] void fail(const std::string& what) const {
    throw MeshFileError(m_name + ": FBX binary weft cannot read: byte " + std::to_string(m_cursor) +
                        ": " + what);
  }

  FbxBytes m_bytes;
  std::string m_name;
  std::uint64_t m_cursor = 0;
  bool m_long = false, m_done = false;
  std::vector<std::uint64_t> m_open;  // end offsets of the nodes whose nested list is being read
};

// An element of a top-level Objects or Connections scope: its key and first data tokens.
struct FbxElement {
  FbxToken key;
  std::vector<FbxToken> data;
};

// assimp's Parser, Scope and Element (FBXParser.cpp): a scope is keys, each followed by data
// tokens (commas between) and perhaps a nested scope in brackets; a `}` at the top ends the
// file's root scope. Only the elements of the top-level Objects and Connections scopes are kept.
// (assimp also refuses two data tokens without a comma unless on consecutive lines; accepting
// them here changes nothing in a file assimp reads.)
class FbxParser {
 public:
  FbxParser(FbxTokenizer& tokens, const FbxBytes& bytes, std::string name)
      : m_tokens(tokens), m_bytes(bytes), m_name(std::move(name)) {
    scope(0, Section::root);
  }
  std::vector<FbxElement> objects, connections;

 private:
  enum class Section { root, objects, connections, other };

  const std::optional<FbxToken>& advance() { return m_current = m_tokens.next(); }

  void scope(int depth, Section section) {
    if (depth > max_fbx_scope_depth)
      throw MeshFileError(m_name + ": FBX scopes nested deeper than " +
                          std::to_string(max_fbx_scope_depth) + " at " +
                          m_tokens.where(m_current->where) + " (assimp reads them by recursion)");
    if (!advance()) fail("unexpected end of file");
    while (m_current->type != FbxTokenType::close) {
      if (m_current->type != FbxTokenType::key)
        fail("unexpected token, expected a key", *m_current);
      if (m_current->begin == m_current->end) fail("unexpected content: an empty key", *m_current);
      element(*m_current, depth, section);
      if (!m_current) {
        if (section == Section::root) return;
        fail("unexpected end of file");
      }
    }
  }

  void element(const FbxToken key, int depth, Section section) {
    Section inner = Section::other;
    if (section == Section::root) {
      const std::string k = m_bytes.piece(key.begin, key.end);
      inner = k == "Objects" ? Section::objects : k == "Connections" ? Section::connections : inner;
    }
    FbxElement* kept = nullptr;
    if (section == Section::objects || section == Section::connections) {
      auto& list = section == Section::objects ? objects : connections;
      kept = &list.emplace_back(FbxElement{key, {}});
    }
    do {
      if (!advance()) fail("unexpected end of file, expected closing bracket");
      if (m_current->type == FbxTokenType::data) {
        if (kept && kept->data.size() < 4) kept->data.push_back(*m_current);
        if (!advance()) fail("unexpected end of file, expected bracket, comma or key");
        if (m_current->type == FbxTokenType::data) {
          if (kept && kept->data.size() < 4) kept->data.push_back(*m_current);
          continue;
        }
      }
      if (m_current->type == FbxTokenType::open) {
        scope(depth + 1, inner);
        if (!m_current || m_current->type != FbxTokenType::close) fail("expected closing bracket");
        advance();
        return;
      }
    } while (m_current->type != FbxTokenType::key && m_current->type != FbxTokenType::close);
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw MeshFileError(m_name + ": FBX file weft cannot read: " + what);
  }
  [[noreturn]] void fail(const std::string& what, const FbxToken& at) const {
    fail(m_tokens.where(at.where) + ": " + what);
  }

  FbxTokenizer& m_tokens;
  const FbxBytes& m_bytes;
  std::string m_name;
  std::optional<FbxToken> m_current;
};

// assimp's ParseTokenAsID: a binary 'L' value, or the text's leading decimal digits (an overflow
// gives 0, the root, as in assimp's strtoul10_64); nothing for what assimp refuses.
std::optional<std::uint64_t> fbx_id(const FbxToken& t, const FbxBytes& bytes, bool binary) {
  if (t.type != FbxTokenType::data) return std::nullopt;
  const std::string s = bytes.piece(t.begin, t.end);
  if (binary) {
    if (s.size() < 9 || s[0] != 'L') return std::nullopt;
    std::uint64_t id = 0;
    for (int k = 0; k < 8; ++k)
      id |= std::uint64_t{static_cast<unsigned char>(s[1 + k])} << (8 * k);
    return id;
  }
  if (s.empty() || s[0] < '0' || s[0] > '9') return std::nullopt;
  std::uint64_t id = 0;
  for (const char c : s) {
    if (c < '0' || c > '9') break;
    const std::uint64_t next = id * 10 + static_cast<std::uint64_t>(c - '0');
    if (next < id) return 0;
    id = next;
  }
  return id;
}

// assimp's ParseTokenAsString: a binary 'S' value, or the text between double quotes.
std::optional<std::string> fbx_string(const FbxToken& t, const FbxBytes& bytes, bool binary) {
  if (t.type != FbxTokenType::data) return std::nullopt;
  const std::string s = bytes.piece(t.begin, t.end);
  if (binary) {
    if (s.size() < 5 || s[0] != 'S') return std::nullopt;
    return s.substr(5);
  }
  if (s.size() < 2 || s.front() != '"' || s.back() != '"') return std::nullopt;
  return s.substr(1, s.size() - 2);
}

// Each model's parent links: connections other than "PP" from a model (an object whose key is
// "Model", the only ones assimp's node conversion follows) to a model or the root.
std::map<std::uint64_t, std::vector<std::uint64_t>> fbx_parent_links(const FbxParser& parsed,
                                                                     const FbxBytes& bytes,
                                                                     bool binary) {
  std::set<std::uint64_t> models;
  for (const FbxElement& e : parsed.objects) {
    const std::string key = bytes.piece(e.key.begin, e.key.end);
    if (e.data.empty() || key != "Model") continue;
    if (const auto id = fbx_id(e.data[0], bytes, binary)) models.insert(*id);
  }
  std::map<std::uint64_t, std::vector<std::uint64_t>> parents;
  for (const FbxElement& c : parsed.connections) {
    if (bytes.piece(c.key.begin, c.key.end) != "C" || c.data.size() < 3) continue;
    const auto type = fbx_string(c.data[0], bytes, binary);
    const auto child = fbx_id(c.data[1], bytes, binary), parent = fbx_id(c.data[2], bytes, binary);
    if (!type || *type == "PP" || !child || !parent) continue;
    if (models.count(*child) && (*parent == 0 || models.count(*parent)))
      parents[*child].push_back(*parent);
  }
  return parents;
}

// One parent link a model, no cycle, at most max_fbx_model_depth levels.
void check_fbx_models(const std::map<std::uint64_t, std::vector<std::uint64_t>>& parents,
                      const std::string& name) {
  for (const auto& [model, links] : parents)
    if (links.size() > 1) {
      std::string to;
      for (std::size_t k = 0; k < links.size() && k < 4; ++k)
        to += (k ? ", " : "") + std::to_string(links[k]);
      throw MeshFileError(name + ": FBX model " + std::to_string(model) + " has " +
                          std::to_string(links.size()) + " parent connections (to " + to +
                          (links.size() > 4 ? ", …" : "") + "); a model has one parent");
    }
  std::map<std::uint64_t, int> depth_of;  // models whose depth is known
  for (const auto& start : parents) {
    std::vector<std::uint64_t> path;  // from `start` up to a model of known depth or the top
    std::set<std::uint64_t> on_path;
    std::uint64_t at = start.first;
    while (at != 0 && parents.count(at) && !depth_of.count(at)) {
      if (!on_path.insert(at).second) {
        std::string cycle;
        const auto first = std::find(path.begin(), path.end(), at);
        for (auto m = first; m != path.end() && m - first < 8; ++m)
          cycle += std::to_string(*m) + " → ";
        throw MeshFileError(name + ": FBX models connected in a cycle (" + cycle +
                            (path.end() - first > 8 ? "… → " : "") + std::to_string(at) +
                            "): a model cannot be its own ancestor");
      }
      path.push_back(at);
      at = parents.at(at).front();
    }
    int depth = at == 0 ? 0 : depth_of.count(at) ? depth_of.at(at) : 1;
    for (auto m = path.rbegin(); m != path.rend(); ++m) {
      if (++depth > max_fbx_model_depth)
        throw MeshFileError(name + ": FBX model " + std::to_string(*m) + " is nested " +
                            std::to_string(depth) + " models deep, more than " +
                            std::to_string(max_fbx_model_depth));
      depth_of[*m] = depth;
    }
  }
}

}  // namespace

void check_fbx(std::string_view bytes, const std::string& name) {
  const FbxBytes file(bytes);
  const bool binary = bytes.substr(0, 18) == "Kaydara FBX Binary";
  std::optional<FbxTextTokenizer> text;
  std::optional<FbxBinaryTokenizer> binary_text;
  FbxTokenizer& tokens = binary ? static_cast<FbxTokenizer&>(binary_text.emplace(bytes, name))
                                : text.emplace(bytes, name);
  const FbxParser parsed(tokens, file, name);
  check_fbx_models(fbx_parent_links(parsed, file, binary), name);
}

}  // namespace weft::app
