#include "geardyn/meshio/nastran_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include "geardyn/core/text.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/meshio/element_ordering.hpp"

namespace geardyn::meshio {
namespace {

namespace fs = std::filesystem;
using solid::ElementType;

constexpr int kMaxIncludeDepth = 64;
constexpr std::string_view kSupported =
    "GRID, CORD2R, CORD2C, CORD2S, CTETRA, CHEXA, CPENTA, PSOLID, MAT1, CONM2, CELAS1, PELAS, "
    "CELAS2, RBE2, RBE3, SPC1, ASET, ASET1, QSET, QSET1, BSET, BSET1, CSET, CSET1";

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

// ---------------------------------------------------------------------------------------------
// Physical lines -> entries (cards)

struct Field {
  std::string text;  // trimmed
  int line = 0;
  int column = 0;  // 1-based column of the first character (of the field's start when blank)
};

struct Card {
  std::string name;  // upper case, without the large-field '*'
  int file = 0;      // index into DeckParser::files_
  int line = 0;
  int column = 1;
  std::vector<Field> data;  // data[i] is Nastran field i + 2 of the entry
};

// A case control "SET n = ..." of grid ids: ranges [from, to] (from == to for one id), and the
// ids excluded by EXCEPT.
struct CaseSet {
  long id = 0;
  int file = 0;
  int line = 0;
  std::vector<std::pair<long, long>> ranges;
  std::set<long> except;
};

// One physical line split into its first field (name or continuation marker) and data fields.
struct SplitLine {
  Field first;
  std::vector<Field> data;
  int per_line = 8;  // data fields one such line holds: 8 (small / free), 4 (large)
};

// Fixed-format fields after expanding tabs to 8-column stops; columns reported are those of the
// raw line.
SplitLine split_fixed(std::string_view raw, int line) {
  std::string text;
  std::vector<int> raw_column;
  for (std::size_t r = 0; r < raw.size() && text.size() < 80; ++r) {
    if (raw[r] == '\t') {
      do {
        text.push_back(' ');
        raw_column.push_back(static_cast<int>(r) + 1);
      } while (text.size() % 8 != 0);
    } else {
      text.push_back(raw[r]);
      raw_column.push_back(static_cast<int>(r) + 1);
    }
  }
  if (text.size() > 80) text.resize(80);  // columns past 80 are not part of the entry
  const auto field = [&](std::size_t start, std::size_t width) {
    Field f;
    f.line = line;
    f.column = start < raw_column.size() ? raw_column[start] : static_cast<int>(raw.size()) + 1;
    if (start >= text.size()) return f;
    const std::string_view part = std::string_view(text).substr(start, width);
    std::size_t lead = 0;
    while (lead < part.size() && is_space(part[lead])) ++lead;
    f.text = std::string(trim(part));
    if (lead < part.size()) f.column = raw_column[start + lead];
    return f;
  };
  SplitLine out;
  out.first = field(0, 8);
  const bool large = (!out.first.text.empty() && out.first.text.back() == '*') ||
                     (!out.first.text.empty() && out.first.text.front() == '*');
  out.per_line = large ? 4 : 8;
  const std::size_t width = large ? 16 : 8;
  for (int k = 0; k < out.per_line; ++k) out.data.push_back(field(8 + k * width, width));
  return out;
}

// Free-field line: fields separated by commas; a trailing field after the data is the
// continuation marker.
SplitLine split_free(std::string_view raw, int line, const std::string& file) {
  std::vector<Field> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = raw.find(',', start);
    const std::string_view part =
        raw.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    Field f;
    f.line = line;
    std::size_t lead = 0;
    while (lead < part.size() && is_space(part[lead])) ++lead;
    f.column = static_cast<int>(start + lead) + 1;
    f.text = std::string(trim(part));
    parts.push_back(std::move(f));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  SplitLine out;
  out.first = parts.front();
  const bool large = (!out.first.text.empty() && out.first.text.back() == '*') ||
                     (!out.first.text.empty() && out.first.text.front() == '*');
  out.per_line = large ? 4 : 8;
  const std::size_t max_parts = static_cast<std::size_t>(out.per_line) + 2;  // + marker
  if (parts.size() > max_parts)
    throw InputError(
        SourceLocation{file, line, parts[max_parts].column}, "free-field line",
        fmt::format("at most {} data fields and a continuation marker per line", out.per_line),
        fmt::format("{} fields", parts.size()),
        "continue the entry on a new line starting with ','");
  const std::size_t data_end = std::min(parts.size(), static_cast<std::size_t>(out.per_line) + 1);
  out.data.assign(parts.begin() + 1, parts.begin() + static_cast<std::ptrdiff_t>(data_end));
  return out;
}

bool parse_integer(std::string_view text, long& value) {
  if (text.empty()) return false;
  if (text.front() == '+') text.remove_prefix(1);
  if (text.empty() || text.front() == '+') return false;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && ptr == text.data() + text.size();
}

bool starts_with_ci(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i)
    if (std::toupper(static_cast<unsigned char>(s[i])) != prefix[i]) return false;
  return true;
}

class DeckParser {
 public:
  DeckParser(const NastranOptions& options, NastranDeck& deck) : options_(options), deck_(deck) {}

  void parse_top(std::string_view text, const std::string& file_name) {
    include_stack_.push_back(stack_key(file_name));
    parse_text(text, file_name, /*top=*/true, 0);
  }

  std::vector<std::string> files_;
  std::vector<Card> cards_;
  std::vector<CaseSet> case_sets_;

 private:
  static std::string stack_key(const std::string& file) {
    std::error_code ec;
    const fs::path canonical = fs::weakly_canonical(fs::path(file), ec);
    return ec ? file : canonical.string();
  }

  void unsupported(const std::string& name, const std::string& file, int line, int column,
                   const std::string& reason) {
    if (options_.unsupported_is_error)
      throw InputError(SourceLocation{file, line, column}, name,
                       reason.empty() ? fmt::format("a supported bulk data entry ({})", kSupported)
                                      : "a supported form of this entry",
                       reason.empty() ? name : reason,
                       "NastranOptions::unsupported_is_error is set; clear it to skip and list "
                       "unsupported entries");
    deck_.unsupported.push_back(UnsupportedCard{name, file, line, reason});
  }

  void flush() {
    if (pending_) cards_.push_back(std::move(*pending_));
    pending_.reset();
  }

  void parse_text(std::string_view text, const std::string& file_name, bool top, int depth) {
    const int file_index = static_cast<int>(files_.size());
    files_.push_back(file_name);
    std::vector<std::string_view> lines;
    for (std::size_t start = 0; start <= text.size();) {
      std::size_t end = text.find('\n', start);
      if (end == std::string_view::npos) end = text.size();
      std::string_view l = text.substr(start, end - start);
      if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
      lines.push_back(l);
      start = end + 1;
    }
    std::size_t first = 0;
    if (top) {
      for (std::size_t i = 0; i < lines.size(); ++i) {
        if (is_begin_bulk(lines[i])) {
          first = i + 1;
          break;
        }
      }
      if (first > 0) read_case_sets(lines, first - 1, file_name, file_index);
    }
    for (std::size_t i = first; i < lines.size() && !stopped_; ++i) {
      const std::string_view raw = lines[i];
      const int line = static_cast<int>(i) + 1;
      if (is_include(raw)) {
        flush();
        include(lines, i, file_name, depth);
        continue;
      }
      std::string_view content = raw.substr(0, raw.find('$'));
      if (trim(content).empty()) continue;
      const std::string head = upper(trim(content).substr(0, 10));
      if (head.rfind("ENDDATA", 0) == 0) {
        stopped_ = true;
        break;
      }
      if (head.rfind("BEGIN", 0) == 0) {
        flush();
        if (is_begin_bulk(content)) continue;
        // BEGIN SUPER=n and similar: the rest of the deck belongs to other parts.
        unsupported("BEGIN", file_name, line, 1,
                    "BEGIN " + std::string(trim(trim(content).substr(5))) +
                        " (partitioned bulk data; the rest of the deck is skipped)");
        stopped_ = true;
        break;
      }
      SplitLine split = content.find(',') != std::string_view::npos
                            ? split_free(content, line, file_name)
                            : split_fixed(content, line);
      const std::string& marker = split.first.text;
      const bool continuation = marker.empty() || marker.front() == '+' || marker.front() == '*';
      if (continuation) {
        if (!pending_)
          throw InputError(SourceLocation{file_name, line, split.first.column}, "continuation",
                           "an entry name in field 1 (a continuation line must follow an entry)",
                           marker.empty() ? "a blank field 1" : "'" + marker + "'");
        append(*pending_, split);
        continue;
      }
      flush();
      Card card;
      card.name = upper(marker);
      if (!card.name.empty() && card.name.back() == '*') card.name.pop_back();
      card.file = file_index;
      card.line = line;
      card.column = split.first.column;
      append(card, split);
      pending_ = std::move(card);
    }
    flush();
  }

  static void append(Card& card, const SplitLine& split) {
    const std::size_t per_line = static_cast<std::size_t>(split.per_line);
    const std::size_t padded = (card.data.size() + per_line - 1) / per_line * per_line;
    while (card.data.size() < padded) {
      Field blank;
      blank.line = split.first.line;
      blank.column = split.first.column;
      card.data.push_back(blank);
    }
    for (const Field& f : split.data) card.data.push_back(f);
  }

  // Case control (after CEND, or the whole text before BEGIN BULK when there is no CEND):
  // "SET n = i1, i2, i3 THRU i4 EXCEPT i5, ..." with continuation lines after a trailing comma.
  // Sets of anything but integers (ALL, real values, labels) are listed as unsupported.
  void read_case_sets(const std::vector<std::string_view>& lines, std::size_t end,
                      const std::string& file_name, int file_index) {
    const auto content = [&](std::size_t k) {
      return upper(trim(lines[k].substr(0, lines[k].find('$'))));
    };
    std::size_t begin = 0;
    for (std::size_t i = 0; i < end; ++i)
      if (content(i) == "CEND") begin = i + 1;
    for (std::size_t i = begin; i < end; ++i) {
      std::string text = content(i);
      if (text.rfind("SET", 0) != 0 || text.size() < 4 || !is_space(text[3])) continue;
      const int line = static_cast<int>(i) + 1;
      while (!text.empty() && text.back() == ',' && i + 1 < end) {
        ++i;
        text.push_back(' ');
        text.append(content(i));
      }
      const std::size_t equals = text.find('=');
      long id = 0;
      if (equals == std::string::npos ||
          !parse_integer(std::string(trim(std::string_view(text).substr(3, equals - 3))), id) ||
          id <= 0) {
        unsupported("SET", file_name, line, 1, "a case control SET without 'n ='");
        continue;
      }
      std::string items = text.substr(equals + 1);
      std::replace(items.begin(), items.end(), ',', ' ');
      std::istringstream words(items);
      std::vector<std::string> w{std::istream_iterator<std::string>(words), {}};
      CaseSet set{id, file_index, line, {}, {}};
      if (!parse_case_items(w, set)) {
        unsupported("SET", file_name, line, 1,
                    fmt::format("SET {} is not a list of ids (only grid-id sets are read)", id));
        continue;
      }
      case_sets_.push_back(std::move(set));
    }
  }

  static bool parse_case_items(const std::vector<std::string>& w, CaseSet& set) {
    bool excepting = false;
    for (std::size_t k = 0; k < w.size(); ++k) {
      long a = 0, b = 0;
      if (w[k] == "EXCEPT") {
        if (set.ranges.empty() || set.ranges.back().first == set.ranges.back().second) return false;
        excepting = true;
        continue;
      }
      if (!parse_integer(w[k], a) || a <= 0) return false;
      if (k + 2 < w.size() && w[k + 1] == "THRU") {
        if (!parse_integer(w[k + 2], b) || b < a) return false;
        set.ranges.emplace_back(a, b);
        excepting = false;
        k += 2;
        continue;
      }
      // EXCEPT lists ids inside the preceding range; the first id outside ends the list.
      if (excepting && a >= set.ranges.back().first && a <= set.ranges.back().second) {
        set.except.insert(a);
        continue;
      }
      excepting = false;
      set.ranges.emplace_back(a, a);
    }
    return !set.ranges.empty();
  }

  static bool is_begin_bulk(std::string_view line) {
    std::istringstream words{upper(line.substr(0, line.find('$')))};
    std::string a, b;
    words >> a >> b;
    return a == "BEGIN" && b == "BULK";
  }

  static bool is_include(std::string_view raw) {
    if (!starts_with_ci(raw, "INCLUDE")) return false;
    return raw.size() == 7 || is_space(raw[7]) || raw[7] == '\'' || raw[7] == '"';
  }

  // INCLUDE 'name' (the quoted name may continue over the following lines) or INCLUDE name.
  void include(const std::vector<std::string_view>& lines, std::size_t& i,
               const std::string& file_name, int depth) {
    const int line = static_cast<int>(i) + 1;
    const SourceLocation where{file_name, line, 1};
    std::string_view rest = trim(lines[i].substr(7));
    std::string name;
    if (!rest.empty() && (rest.front() == '\'' || rest.front() == '"')) {
      const char quote = rest.front();
      rest.remove_prefix(1);
      while (true) {
        const std::size_t close = rest.find(quote);
        if (close != std::string_view::npos) {
          name += std::string(trim(rest.substr(0, close)));
          break;
        }
        name += std::string(trim(rest));
        if (++i >= lines.size())
          throw InputError(where, "INCLUDE", "a file name closed by a matching quote",
                           "end of file");
        rest = trim(lines[i]);
      }
    } else {
      name = std::string(trim(rest.substr(0, rest.find('$'))));
    }
    if (name.empty()) throw InputError(where, "INCLUDE", "a file name", "nothing");
    if (!options_.allow_include)
      throw InputError(where, "INCLUDE", "no INCLUDE (NastranOptions::allow_include is off)",
                       "INCLUDE '" + name + "'");
    fs::path path(name);
    if (path.is_relative()) path = fs::path(file_name).parent_path() / path;
    if (depth + 1 > kMaxIncludeDepth)
      throw InputError(where, "INCLUDE",
                       fmt::format("at most {} nested INCLUDEs", kMaxIncludeDepth), path.string());
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
      throw InputError(where, "INCLUDE", "an existing file (relative to the including file)",
                       "'" + path.string() + "'");
    const std::string key = stack_key(path.string());
    if (std::find(include_stack_.begin(), include_stack_.end(), key) != include_stack_.end())
      throw InputError(where, "INCLUDE", "no INCLUDE cycle",
                       "'" + path.string() + "' includes itself (directly or indirectly)");
    const std::optional<std::string> content = try_read_file(path);
    if (!content) throw InputError(where, "INCLUDE", "a readable file", "'" + path.string() + "'");
    include_stack_.push_back(key);
    parse_text(*content, path.string(), /*top=*/false, depth + 1);
    include_stack_.pop_back();
  }

  const NastranOptions& options_;
  NastranDeck& deck_;
  std::optional<Card> pending_;
  std::vector<std::string> include_stack_;
  bool stopped_ = false;
};

// ---------------------------------------------------------------------------------------------
// Field access with Nastran types and precise errors

class Entry {
 public:
  Entry(const Card& card, const std::string& file) : card_(card), file_(file) {}

  const Card& card() const { return card_; }
  const std::string& file() const { return file_; }
  SourceLocation where() const { return SourceLocation{file_, card_.line, card_.column}; }

  // Highest field number present (1 = the name).
  int last() const { return static_cast<int>(card_.data.size()) + 1; }

  const Field& field(int n) const {
    static const Field kBlank;
    const std::size_t index = static_cast<std::size_t>(n - 2);
    return n >= 2 && index < card_.data.size() ? card_.data[index] : kBlank;
  }
  const std::string& text(int n) const { return field(n).text; }
  bool blank(int n) const { return text(n).empty(); }

  SourceLocation where(int n) const {
    const Field& f = field(n);
    if (f.line == 0) return SourceLocation{file_, card_.line, 0};
    return SourceLocation{file_, f.line, f.column};
  }
  std::string key(int n, std::string_view name) const {
    return fmt::format("{} field {} ({})", card_.name, n, name);
  }
  [[noreturn]] void fail(int n, std::string_view name, const std::string& expected,
                         std::string found = {}, std::string hint = {}) const {
    if (found.empty()) found = blank(n) ? "a blank field" : "'" + text(n) + "'";
    throw InputError(where(n), key(n, name), expected, std::move(found), std::move(hint));
  }

  long integer(int n, std::string_view name, std::optional<long> fallback = {}) const {
    if (blank(n)) {
      if (fallback) return *fallback;
      fail(n, name, "an integer (required)");
    }
    long value = 0;
    if (!parse_integer(text(n), value)) fail(n, name, "an integer");
    return value;
  }
  long id(int n, std::string_view name) const {
    const long value = integer(n, name);
    if (value <= 0) fail(n, name, "a positive integer id");
    return value;
  }
  double real(int n, std::string_view name, std::optional<double> fallback = {}) const {
    if (blank(n)) {
      if (fallback) return *fallback;
      fail(n, name, "a real number (required)");
    }
    double value = 0;
    if (!parse_nastran_real(text(n), value)) {
      long integer_value = 0;
      fail(n, name, "a finite real number (Nastran form, e.g. 1.0, 1.5-3, 2.+5, 1.E4)", {},
           parse_integer(text(n), integer_value)
               ? "Nastran real fields need a decimal point: write " + text(n) + "."
               : std::string{});
    }
    return value;
  }
  std::optional<double> optional_real(int n, std::string_view name) const {
    if (blank(n)) return std::nullopt;
    return real(n, name);
  }
  // DOF components: distinct digits 1..6 ("123456"); blank allowed only with a fallback.
  std::array<bool, 6> components(int n, std::string_view name) const {
    std::array<bool, 6> on{};
    const std::string& t = text(n);
    if (t.empty()) fail(n, name, "DOF components (digits 1..6, e.g. 123)");
    for (char c : t) {
      if (c < '1' || c > '6' || on[static_cast<std::size_t>(c - '1')])
        fail(n, name, "DOF components: distinct digits 1..6 (e.g. 123456)", {},
             c == '0' ? "scalar points (component 0) are not supported" : std::string{});
      on[static_cast<std::size_t>(c - '1')] = true;
    }
    return on;
  }
  int single_component(int n, std::string_view name) const {
    const std::string& t = text(n);
    if (t.size() != 1 || t[0] < '1' || t[0] > '6')
      fail(n, name, "one DOF component, 1..6", {},
           t == "0" || t.empty() ? "scalar points are not supported: give a GRID and component"
                                 : std::string{});
    return t[0] - '1';
  }
  // Fields past `max_field` must be blank.
  void check_max_fields(int max_field) const {
    for (int n = max_field + 1; n <= last(); ++n)
      if (!blank(n))
        fail(n, "extra", fmt::format("at most {} fields for {}", max_field, card_.name));
  }

 private:
  const Card& card_;
  const std::string& file_;
};

bool is_real_text(std::string_view t) {
  double v = 0;
  return parse_nastran_real(t, v);
}

std::string location_text(const SourceLocation& w) { return fmt::format("{}:{}", w.file, w.line); }

std::string components_text(const std::array<bool, 6>& c) {
  std::string s;
  for (int i = 0; i < 6; ++i)
    if (c[static_cast<std::size_t>(i)]) s.push_back(static_cast<char>('1' + i));
  return s;
}

// ---------------------------------------------------------------------------------------------
// Coordinate systems

struct CoordSystem {
  long id = 0;
  char kind = 'R';  // R rectangular, C cylindrical (r, theta deg, z), S spherical (r, theta, phi)
  long rid = 0;
  Eigen::Vector3d a, b, c;
  const Card* card = nullptr;
  int state = 0;  // 0 unresolved, 1 resolving, 2 resolved
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // columns: local x, y, z in global
};

double deg(double d) { return d * units::kPi / 180.0; }

Eigen::Vector3d to_cartesian(char kind, const Eigen::Vector3d& p) {
  switch (kind) {
    case 'C':
      return {p[0] * std::cos(deg(p[1])), p[0] * std::sin(deg(p[1])), p[2]};
    case 'S':
      return {p[0] * std::sin(deg(p[1])) * std::cos(deg(p[2])),
              p[0] * std::sin(deg(p[1])) * std::sin(deg(p[2])), p[0] * std::cos(deg(p[1]))};
    default:
      return p;
  }
}

// The displacement axes of system `s` at the global point x (columns: components 1, 2, 3).
Eigen::Matrix3d local_axes(const CoordSystem& s, const Eigen::Vector3d& x) {
  if (s.kind == 'R') return s.axes;
  const Eigen::Vector3d p = s.axes.transpose() * (x - s.origin);
  const double phi = std::atan2(p[1], p[0]);  // azimuth in the local xy plane
  Eigen::Matrix3d local;
  if (s.kind == 'C') {
    local.col(0) << std::cos(phi), std::sin(phi), 0;
    local.col(1) << -std::sin(phi), std::cos(phi), 0;
    local.col(2) << 0, 0, 1;
  } else {
    const double theta = std::atan2(std::hypot(p[0], p[1]), p[2]);  // from the local z axis
    local.col(0) << std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
        std::cos(theta);
    local.col(1) << std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi),
        -std::sin(theta);
    local.col(2) << -std::sin(phi), std::cos(phi), 0;
  }
  return s.axes * local;
}

bool is_identity(const Eigen::Matrix3d& axes) {
  return (axes - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-12;
}

// Components that mean the same in any axes: the translations all or none, the rotations all or
// none.
bool axes_independent(const std::array<bool, 6>& c) {
  return (c[0] == c[1] && c[1] == c[2]) && (c[3] == c[4] && c[4] == c[5]);
}

// ---------------------------------------------------------------------------------------------
// Building the mesh

struct Grid {
  long id = 0;
  long cp = 0, cd = 0;
  Eigen::Vector3d x_cp;
  const Card* card = nullptr;
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  Eigen::Matrix3d cd_axes = Eigen::Matrix3d::Identity();
};

struct Mat1 {
  long id = 0;
  double E = 0, nu = 0, rho = 0;
  bool has_E = false, has_G = false, has_nu = false;
  const Card* card = nullptr;
  int mesh_index = -1;
};

struct Pelas {
  double k = 0;
  const Card* card = nullptr;
  int field = 0;  // field of K on the card
};

class DeckBuilder {
 public:
  DeckBuilder(const NastranOptions& options, NastranDeck& deck, const DeckParser& parser)
      : options_(options), deck_(deck), parser_(parser), mesh_(deck.mesh) {}

  void build() {
    std::map<std::string, std::vector<const Card*>> by_name;
    for (const Card& c : parser_.cards_) {
      static const std::set<std::string> kKnown = {
          "GRID", "CORD2R", "CORD2C", "CORD2S", "CTETRA", "CHEXA", "CPENTA", "PSOLID",
          "MAT1", "CONM2",  "CELAS1", "PELAS",  "CELAS2", "RBE2",  "RBE3",   "SPC1",
          "ASET", "ASET1",  "QSET",   "QSET1",  "BSET",   "BSET1", "CSET",   "CSET1"};
      if (kKnown.count(c.name) != 0) {
        by_name[c.name].push_back(&c);
      } else {
        unsupported(c, c.name.empty() ? "?" : c.name, "");
      }
    }
    const auto cards = [&](const char* name) -> const std::vector<const Card*>& {
      static const std::vector<const Card*> kNone;
      const auto it = by_name.find(name);
      return it == by_name.end() ? kNone : it->second;
    };
    for (const char* name : {"CORD2R", "CORD2C", "CORD2S"})
      for (const Card* c : cards(name)) read_cord2(*c);
    for (auto& [id, s] : coords_) resolve(s);
    for (const Card* c : cards("GRID")) read_grid(*c);
    place_grids();
    for (const Card* c : cards("MAT1")) read_mat1(*c);
    for (const Card* c : cards("PSOLID")) read_psolid(*c);
    for (const Card* c : cards("PELAS")) read_pelas(*c);
    for (const Card* c : cards("CTETRA")) read_solid(*c, ElementType::Tet4, ElementType::Tet10);
    for (const Card* c : cards("CHEXA")) read_solid(*c, ElementType::Hex8, ElementType::Hex20);
    for (const Card* c : cards("CPENTA")) read_solid(*c, ElementType::Wedge6, ElementType::Wedge15);
    finish_elements();
    for (const Card* c : cards("CONM2")) read_conm2(*c);
    for (const Card* c : cards("CELAS1")) read_celas(*c, /*with_property=*/true);
    for (const Card* c : cards("CELAS2")) read_celas(*c, /*with_property=*/false);
    for (const Card* c : cards("RBE2")) read_rbe2(*c);
    for (const Card* c : cards("RBE3")) read_rbe3(*c);
    for (const Card* c : cards("SPC1")) read_spc1(*c);
    for (const char* name : {"ASET", "QSET", "BSET", "CSET"}) {
      for (const Card* c : cards(name)) read_dof_set_pairs(*c);
      for (const Card* c : cards((std::string(name) + "1").c_str())) read_dof_set1(*c);
    }
    for (const CaseSet& set : parser_.case_sets_) read_case_set(set);
    finish_constraints();
  }

 private:
  Entry entry(const Card& c) const {
    return Entry(c, parser_.files_[static_cast<std::size_t>(c.file)]);
  }
  const std::string& file_of(const Card& c) const {
    return parser_.files_[static_cast<std::size_t>(c.file)];
  }
  void unsupported(const Card& c, const std::string& name, const std::string& reason) {
    if (options_.unsupported_is_error)
      throw InputError(SourceLocation{file_of(c), c.line, c.column}, name,
                       reason.empty() ? fmt::format("a supported bulk data entry ({})", kSupported)
                                      : "a supported form of this entry",
                       reason.empty() ? name : reason,
                       "NastranOptions::unsupported_is_error is set; clear it to skip and list "
                       "unsupported entries");
    deck_.unsupported.push_back(UnsupportedCard{name, file_of(c), c.line, reason});
  }
  void warn(const Entry& e, int n, const std::string& message) {
    const SourceLocation w = e.where(n);
    deck_.warnings.push_back(fmt::format("{}:{}: {} {}", w.file, w.line, e.card().name, message));
  }

  // Element ids are unique over all element entries (solids, masses, springs, rigid elements).
  void register_element_id(const Entry& e, long eid) {
    const auto [it, inserted] = element_ids_.emplace(eid, e.where());
    if (!inserted)
      e.fail(2, "EID", "an element id not used by another element", std::to_string(eid),
             "also used at " + location_text(it->second));
  }

  // --- coordinate systems
  void read_cord2(const Card& card) {
    const Entry e = entry(card);
    e.check_max_fields(12);
    CoordSystem s;
    s.id = e.id(2, "CID");
    s.kind = card.name.back();
    s.rid = e.integer(3, "RID", 0);
    if (s.rid < 0) e.fail(3, "RID", "a coordinate system id >= 0");
    s.a = {e.real(4, "A1", 0.0), e.real(5, "A2", 0.0), e.real(6, "A3", 0.0)};
    s.b = {e.real(7, "B1", 0.0), e.real(8, "B2", 0.0), e.real(9, "B3", 0.0)};
    s.c = {e.real(10, "C1", 0.0), e.real(11, "C2", 0.0), e.real(12, "C3", 0.0)};
    s.card = &card;
    const auto [it, inserted] = coords_.emplace(s.id, s);
    if (!inserted)
      e.fail(2, "CID", "a coordinate system id not defined before", std::to_string(s.id),
             "first defined at " + location_text(entry(*it->second.card).where()));
  }

  void resolve(CoordSystem& s) {
    if (s.state == 2) return;
    const Entry e = entry(*s.card);
    if (s.state == 1)
      e.fail(3, "RID", "a reference system chain that ends in the basic system (0)",
             fmt::format("a cycle through system {}", s.id));
    s.state = 1;
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
    char kind = 'R';
    if (s.rid != 0) {
      const auto it = coords_.find(s.rid);
      if (it == coords_.end())
        e.fail(3, "RID", "a coordinate system defined by CORD2R/C/S (or 0)", std::to_string(s.rid));
      resolve(it->second);
      origin = it->second.origin;
      axes = it->second.axes;
      kind = it->second.kind;
    }
    const Eigen::Vector3d a = origin + axes * to_cartesian(kind, s.a);
    const Eigen::Vector3d b = origin + axes * to_cartesian(kind, s.b);
    const Eigen::Vector3d c = origin + axes * to_cartesian(kind, s.c);
    const double scale = std::max({(b - a).norm(), (c - a).norm(), 1e-300});
    const Eigen::Vector3d z = b - a;
    const Eigen::Vector3d y = z.cross(c - a);
    if (!(z.norm() > 1e-12 * scale) || !(y.norm() > 1e-12 * scale * scale))
      e.fail(4, "A1", "points A, B, C not on one line (A origin, B on the z axis, C in xz plane)",
             fmt::format("A = ({}, {}, {}), B = ({}, {}, {}), C = ({}, {}, {})", s.a[0], s.a[1],
                         s.a[2], s.b[0], s.b[1], s.b[2], s.c[0], s.c[1], s.c[2]));
    s.origin = a;
    s.axes.col(2) = z.normalized();
    s.axes.col(1) = y.normalized();
    s.axes.col(0) = s.axes.col(1).cross(s.axes.col(2));
    s.state = 2;
  }

  const CoordSystem* system(const Entry& e, int n, std::string_view name, long cid) {
    if (cid == 0) return nullptr;
    const auto it = coords_.find(cid);
    if (it == coords_.end())
      e.fail(n, name, "a coordinate system defined by CORD2R, CORD2C or CORD2S (or 0)", {},
             "CORD1R/C/S and other systems are not supported");
    return &it->second;
  }

  // --- grids
  void read_grid(const Card& card) {
    const Entry e = entry(card);
    e.check_max_fields(9);
    Grid g;
    g.id = e.id(2, "ID");
    g.cp = e.integer(3, "CP", 0);
    g.x_cp = {e.real(4, "X1", 0.0), e.real(5, "X2", 0.0), e.real(6, "X3", 0.0)};
    g.cd = e.integer(7, "CD", 0);
    if (g.cd < 0)
      e.fail(7, "CD", "a coordinate system id >= 0", {}, "fluid grids (-1) are not supported");
    g.card = &card;
    if (!e.blank(8)) (void)e.components(8, "PS");
    if (e.integer(9, "SEID", 0) != 0) unsupported(card, "GRID", "GRID SEID (superelements)");
    const auto [it, inserted] = grid_index_.emplace(g.id, static_cast<int>(grids_.size()));
    if (!inserted)
      e.fail(2, "ID", "a GRID id not defined before", std::to_string(g.id),
             "first defined at " +
                 location_text(entry(*grids_[static_cast<std::size_t>(it->second)].card).where()));
    grids_.push_back(g);
  }

  void place_grids() {
    std::sort(grids_.begin(), grids_.end(),
              [](const Grid& a, const Grid& b) { return a.id < b.id; });
    for (std::size_t i = 0; i < grids_.size(); ++i) {
      Grid& g = grids_[i];
      grid_index_[g.id] = static_cast<int>(i);
      const Entry e = entry(*g.card);
      g.x = g.x_cp;
      if (const CoordSystem* cp = system(e, 3, "CP", g.cp))
        g.x = cp->origin + cp->axes * to_cartesian(cp->kind, g.x_cp);
      if (const CoordSystem* cd = system(e, 7, "CD", g.cd)) g.cd_axes = local_axes(*cd, g.x);
      mesh_.node_ids.push_back(g.id);
      mesh_.coords.push_back(g.x);
    }
    // Permanent single-point constraints (GRID PS).
    for (std::size_t i = 0; i < grids_.size(); ++i) {
      const Entry e = entry(*grids_[i].card);
      if (e.blank(8)) continue;
      const std::array<bool, 6> c = e.components(8, "PS");
      check_axes(e, 8, "PS", static_cast<int>(i), c);
      add_constraint(static_cast<int>(i), c, e.where());
    }
  }

  int node(const Entry& e, int n, std::string_view name) {
    const long id = e.id(n, name);
    const auto it = grid_index_.find(id);
    if (it == grid_index_.end())
      e.fail(n, name, "the id of a GRID in the deck", std::to_string(id));
    return it->second;
  }

  void check_axes(const Entry& e, int n, std::string_view name, int node_index,
                  const std::array<bool, 6>& c) const {
    const Grid& g = grids_[static_cast<std::size_t>(node_index)];
    if (is_identity(g.cd_axes) || axes_independent(c)) return;
    e.fail(n, name, "components that mean the same in global axes (123 and 456 each all or none)",
           components_text(c),
           fmt::format("GRID {} has CD = {}, whose axes are rotated; geardyn applies DOF "
                       "components in global axes",
                       g.id, g.cd));
  }

  // --- materials and properties
  void read_mat1(const Card& card) {
    const Entry e = entry(card);
    e.check_max_fields(13);
    Mat1 m;
    m.id = e.id(2, "MID");
    m.card = &card;
    const std::optional<double> E = e.optional_real(3, "E");
    const std::optional<double> G = e.optional_real(4, "G");
    const std::optional<double> nu = e.optional_real(5, "NU");
    m.rho = e.real(6, "RHO", 0.0);
    for (int n = 7; n <= 13; ++n)
      if (!e.blank(n) && n != 13)
        (void)e.real(n, n == 7 ? "A" : n == 8 ? "TREF" : n == 9 ? "GE" : "ST/SC/SS");
    if (e.real(9, "GE", 0.0) != 0.0)
      warn(e, 9, "GE (structural damping) is ignored: give damping in the model file");
    if (!E && !G) e.fail(3, "E", "E or G (both are blank)");
    // Nastran's rule: one blank of E, G, NU follows from E = 2 (1 + NU) G; E alone or G alone
    // gives NU = 0 and the other modulus 0.
    if (E && G && nu) {
      m.E = *E;
      m.nu = *nu;
      if (std::abs(1.0 - *E / (2.0 * (1.0 + *nu) * *G)) > 0.01)
        warn(e, 3,
             fmt::format("E = {}, G = {}, NU = {} do not satisfy E = 2 (1 + NU) G within 1 %; "
                         "solids use E and NU",
                         *E, *G, *nu));
    } else if (E && G) {
      m.E = *E;
      m.nu = *E / (2.0 * *G) - 1.0;
    } else if (E && nu) {
      m.E = *E;
      m.nu = *nu;
    } else if (G && nu) {
      m.E = 2.0 * (1.0 + *nu) * *G;
      m.nu = *nu;
    } else {
      m.E = E.value_or(0.0);
      m.nu = 0.0;
    }
    const auto [it, inserted] = mat1_.emplace(m.id, m);
    if (!inserted)
      e.fail(2, "MID", "a material id not defined before", std::to_string(m.id),
             "first defined at " + location_text(entry(*it->second.card).where()));
  }

  void register_property(const Entry& e, long pid, int field) {
    const auto [it, inserted] = property_ids_.emplace(pid, e.where(field));
    if (!inserted)
      e.fail(field, "PID", "a property id not defined before", std::to_string(pid),
             "first defined at " + location_text(it->second));
  }

  void read_psolid(const Card& card) {
    const Entry e = entry(card);
    e.check_max_fields(8);
    const long pid = e.id(2, "PID");
    register_property(e, pid, 2);
    const long mid = e.id(3, "MID");
    if (upper(e.text(8)) == "PFLUID") {
      unsupported(card, "PSOLID", "PSOLID FCTN = PFLUID (fluid elements)");
      return;
    }
    psolid_.emplace(pid, std::make_pair(mid, &card));
  }

  void read_pelas(const Card& card) {
    const Entry e = entry(card);
    e.check_max_fields(9);
    for (int base : {2, 6}) {
      if (base == 6 && e.blank(6) && e.blank(7) && e.blank(8) && e.blank(9)) break;
      const long pid = e.id(base, "PID");
      register_property(e, pid, base);
      Pelas p;
      p.k = e.real(base + 1, "K");
      p.card = &card;
      p.field = base + 1;
      if (e.real(base + 2, "GE", 0.0) != 0.0)
        warn(e, base + 2, "GE (structural damping) is ignored: give damping in the model file");
      (void)e.real(base + 3, "S", 0.0);
      pelas_.emplace(pid, p);
    }
  }

  // Material index in the mesh for a MAT1 id referenced by PSOLID `pid`, checked for solids.
  long solid_material(const Entry& element, long pid) {
    const auto p = psolid_.find(pid);
    if (p == psolid_.end())
      element.fail(3, "PID", "the id of a PSOLID in the deck", std::to_string(pid));
    const long mid = p->second.first;
    const Entry prop = entry(*p->second.second);
    const auto m = mat1_.find(mid);
    if (m == mat1_.end()) prop.fail(3, "MID", "the id of a MAT1 in the deck", std::to_string(mid));
    Mat1& mat = m->second;
    if (mat.mesh_index < 0) {
      const Entry me = entry(*mat.card);
      if (!(mat.E > 0) || !std::isfinite(mat.E))
        me.fail(3, "E", "E > 0 for solid elements (from E, or from G and NU)",
                fmt::format("E = {}", mat.E));
      if (!(mat.nu > -1.0 && mat.nu < 0.5))
        me.fail(5, "NU", "-1 < NU < 0.5 for solid elements (given, or from E and G)",
                fmt::format("NU = {}", mat.nu));
      if (mat.rho < 0) me.fail(6, "RHO", "a density >= 0", fmt::format("{}", mat.rho));
      materials_used_.insert(mid);
      mat.mesh_index = 0;  // numbered in finish_elements, in MID order
    }
    return mid;
  }

  // --- solid elements
  struct PendingElement {
    solid::Element element;
    long pid = 0;
    long mid = 0;
  };

  void read_solid(const Card& card, ElementType linear, ElementType quadratic) {
    const Entry e = entry(card);
    const int corners = num_corner_nodes(linear);
    const int total = solid::num_element_nodes(quadratic);
    e.check_max_fields(3 + total);
    const long eid = e.id(2, "EID");
    register_element_id(e, eid);
    const long pid = e.id(3, "PID");
    int mids = 0;
    for (int k = corners; k < total; ++k) mids += e.blank(4 + k) ? 0 : 1;
    if (mids != 0 && mids != total - corners)
      e.fail(4 + corners, fmt::format("G{}", corners + 1),
             fmt::format("all {} mid-edge grids G{}..G{} or none", total - corners, corners + 1,
                         total),
             fmt::format("{} of them", mids), "partially quadratic elements are not supported");
    const ElementType type = mids == 0 ? linear : quadratic;
    std::vector<int> nodes;
    for (int k = 0; k < solid::num_element_nodes(type); ++k) {
      const int n = 4 + k;
      nodes.push_back(node(e, n, fmt::format("G{}", k + 1)));
      for (int j = 0; j < k; ++j)
        if (nodes[static_cast<std::size_t>(j)] == nodes.back())
          e.fail(n, fmt::format("G{}", k + 1), "distinct grids in one element",
                 fmt::format("GRID {} also as G{}", e.text(n), j + 1));
    }
    PendingElement p;
    p.element.type = type;
    p.element.id = eid;
    p.element.nodes = nastran_to_gmsh(type, nodes);
    p.element.where = e.where();
    if (orient_positive(type, p.element.nodes, mesh_.coords) == Orientation::Degenerate)
      e.fail(4, "G1", "an element with non-zero volume",
             fmt::format("{} {} with zero (or undefined) corner volume", card.name, eid));
    p.pid = pid;
    p.mid = solid_material(e, pid);
    elements_.push_back(std::move(p));
  }

  void finish_elements() {
    for (long mid : materials_used_) {
      Mat1& m = mat1_.at(mid);
      m.mesh_index = static_cast<int>(mesh_.materials.size());
      solid::Material material;
      material.name = fmt::format("MAT1_{}", mid);
      material.id = mid;
      material.E = m.E;
      material.nu = m.nu;
      material.rho = m.rho;
      material.where = entry(*m.card).where();
      mesh_.materials.push_back(material);
    }
    std::sort(elements_.begin(), elements_.end(),
              [](const auto& a, const auto& b) { return a.element.id < b.element.id; });
    for (PendingElement& p : elements_) {
      p.element.material = mat1_.at(p.mid).mesh_index;
      mesh_.element_sets[fmt::format("PSOLID_{}", p.pid)].push_back(mesh_.num_elements());
      mesh_.elements.push_back(std::move(p.element));
    }
  }

  // --- masses, springs, rigid elements
  void read_conm2(const Card& card) {
    const Entry e = entry(card);
    e.check_max_fields(15);
    solid::PointMass pm;
    pm.id = e.id(2, "EID");
    register_element_id(e, pm.id);
    pm.node = node(e, 3, "G");
    const long cid = e.integer(4, "CID", 0);
    if (cid < -1) e.fail(4, "CID", "-1, 0 or a coordinate system id");
    pm.mass = e.real(5, "M");
    if (pm.mass < 0) e.fail(5, "M", "a mass >= 0");
    const Eigen::Vector3d x{e.real(6, "X1", 0.0), e.real(7, "X2", 0.0), e.real(8, "X3", 0.0)};
    if (!e.blank(9)) e.fail(9, "(blank)", "a blank field");
    const double i11 = e.real(10, "I11", 0.0), i21 = e.real(11, "I21", 0.0),
                 i22 = e.real(12, "I22", 0.0), i31 = e.real(13, "I31", 0.0),
                 i32 = e.real(14, "I32", 0.0), i33 = e.real(15, "I33", 0.0);
    if (i11 < 0 || i22 < 0 || i33 < 0)
      e.fail(i11 < 0 ? 10 : i22 < 0 ? 12 : 15, "Iii", "moments of inertia >= 0");
    Eigen::Matrix3d inertia;
    inertia << i11, -i21, -i31, -i21, i22, -i32, -i31, -i32, i33;
    const Eigen::Vector3d& position = mesh_.coords[static_cast<std::size_t>(pm.node)];
    if (cid == -1) {
      pm.offset = x - position;
      pm.inertia = inertia;
    } else if (const CoordSystem* s = system(e, 4, "CID", cid)) {
      const Eigen::Matrix3d axes = local_axes(*s, position);
      pm.offset = axes * x;
      pm.inertia = axes * inertia * axes.transpose();
    } else {
      pm.offset = x;
      pm.inertia = inertia;
    }
    pm.where = e.where();
    mesh_.point_masses.push_back(pm);
  }

  void read_celas(const Card& card, bool with_property) {
    const Entry e = entry(card);
    e.check_max_fields(with_property ? 7 : 9);
    solid::Spring s;
    s.id = e.id(2, "EID");
    register_element_id(e, s.id);
    if (with_property) {
      const long pid = e.id(3, "PID");
      const auto it = pelas_.find(pid);
      if (it == pelas_.end())
        e.fail(3, "PID", "the id of a PELAS in the deck", std::to_string(pid));
      s.stiffness = it->second.k;
    } else {
      s.stiffness = e.real(3, "K");
      if (e.real(8, "GE", 0.0) != 0.0)
        warn(e, 8, "GE (structural damping) is ignored: give damping in the model file");
      (void)e.real(9, "S", 0.0);
    }
    int ends = 0;
    for (int end = 0; end < 2; ++end) {
      const int gf = 4 + 2 * end, cf = gf + 1;
      const std::string gname = fmt::format("G{}", end + 1), cname = fmt::format("C{}", end + 1);
      if (e.blank(gf)) {
        if (!e.blank(cf) && e.text(cf) != "0")
          e.fail(cf, cname, "a blank component for a blank (grounded) grid");
        continue;
      }
      const int n = node(e, gf, gname);
      const int c = e.single_component(cf, cname);
      // On a grid with a rotated displacement system (CD) the spring acts along that system's
      // axis c (e.g. radially in a cylindrical CD): a spring with a direction (solid::Spring).
      const Eigen::Matrix3d& axes = grids_[static_cast<std::size_t>(n)].cd_axes;
      const Eigen::Vector3d direction =
          is_identity(axes) ? Eigen::Vector3d::Zero() : Eigen::Vector3d(axes.col(c % 3));
      if (ends == 0) {
        s.node1 = n;
        s.component1 = c;
        s.direction1 = direction;
      } else {
        s.node2 = n;
        s.component2 = c;
        s.direction2 = direction;
      }
      ++ends;
    }
    if (ends == 0) e.fail(4, "G1", "at least one grid (G1 or G2)");
    if (s.node1 == s.node2 && s.component1 == s.component2)
      e.fail(6, "G2", "two different DOFs (the spring connects a DOF to itself)");
    s.where = e.where();
    mesh_.springs.push_back(s);
  }

  // Grid list with "A THRU B" ranges from field `first` on, stopping at the first real field
  // (RBE2 ALPHA). With `skip_missing_in_ranges`, grids missing inside a THRU range are skipped.
  std::vector<int> grid_list(const Entry& e, int first, int& stop, bool skip_missing_in_ranges) {
    std::vector<int> nodes;
    stop = e.last() + 1;
    long last_id = 0;  // 0: no grid id just before (ids are > 0)
    for (int n = first; n <= e.last(); ++n) {
      if (e.blank(n)) continue;
      const std::string t = upper(e.text(n));
      if (t == "THRU") {
        int next = n + 1;
        while (next <= e.last() && e.blank(next)) ++next;
        if (last_id == 0) e.fail(n, "THRU", "a grid id before THRU");
        const long previous = last_id;
        last_id = 0;
        const long to = e.id(next, "G (after THRU)");
        if (to <= previous)
          e.fail(next, "G (after THRU)", fmt::format("an id greater than {}", previous));
        for (long id = previous + 1; id <= to; ++id) {
          const auto it = grid_index_.find(id);
          if (it == grid_index_.end()) {
            if (skip_missing_in_ranges) continue;
            e.fail(next, "G (after THRU)",
                   fmt::format("every grid of {} THRU {} to exist", previous, to),
                   fmt::format("GRID {} is not in the deck", id));
          }
          nodes.push_back(it->second);
        }
        n = next;
        continue;
      }
      if (is_real_text(t)) {
        stop = n;
        break;
      }
      nodes.push_back(node(e, n, "G"));
      last_id = e.id(n, "G");
    }
    return nodes;
  }

  void read_rbe2(const Card& card) {
    const Entry e = entry(card);
    solid::RigidElement r;
    r.kind = solid::RigidElement::Kind::Rigid;
    r.id = e.id(2, "EID");
    register_element_id(e, r.id);
    r.reference = node(e, 3, "GN");
    r.components = e.components(4, "CM");
    int stop = 0;
    r.nodes = grid_list(e, 5, stop, /*skip_missing_in_ranges=*/false);
    if (r.nodes.empty()) e.fail(5, "GM1", "at least one dependent grid");
    if (stop <= e.last()) {
      (void)e.real(stop, "ALPHA");
      int n = stop + 1;
      while (n <= e.last() && e.blank(n)) ++n;
      if (n <= e.last()) (void)e.real(n, "TREF");
      e.check_max_fields(n);
    }
    for (int n : r.nodes) {
      if (n == r.reference)
        e.fail(3, "GN", "an independent grid that is not also dependent",
               std::to_string(grids_[static_cast<std::size_t>(n)].id));
      check_axes(e, 4, "CM", n, r.components);
    }
    r.where = e.where();
    mesh_.rigid_elements.push_back(std::move(r));
  }

  void read_rbe3(const Card& card) {
    const Entry e = entry(card);
    solid::RigidElement r;
    r.kind = solid::RigidElement::Kind::Averaging;
    r.id = e.id(2, "EID");
    register_element_id(e, r.id);
    if (!e.blank(3)) e.fail(3, "(blank)", "a blank field");
    r.reference = node(e, 4, "REFGRID");
    r.components = e.components(5, "REFC");
    check_axes(e, 5, "REFC", r.reference, r.components);
    std::string unsupported_reason;
    int n = 6;
    const auto next_nonblank = [&](int from) {
      while (from <= e.last() && e.blank(from)) ++from;
      return from;
    };
    while ((n = next_nonblank(n)) <= e.last()) {
      const std::string t = upper(e.text(n));
      if (t == "UM") {
        unsupported(card, "RBE3", "RBE3 UM (dependent DOFs moved to other grids)");
        return;
      }
      if (t == "ALPHA" || t == "TREF") {
        const int v = next_nonblank(n + 1);
        (void)e.real(v, t);
        n = v + 1;
        continue;
      }
      if (!is_real_text(t))
        e.fail(n, "WTi", "a weight (real) that starts a group WTi Ci Gi,1 Gi,2 ...", {},
               "weights need a decimal point, e.g. 1.0");
      const double weight = e.real(n, "WTi");
      if (!(weight > 0)) e.fail(n, "WTi", "a weight > 0");
      const int cf = next_nonblank(n + 1);
      const std::array<bool, 6> c = e.components(cf, "Ci");
      if (c != std::array<bool, 6>{true, true, true, false, false, false})
        unsupported_reason =
            fmt::format("RBE3 independent components Ci = {} (only 123)", components_text(c));
      int count = 0;
      for (n = cf + 1; n <= e.last(); ++n) {
        if (e.blank(n)) continue;
        const std::string g = upper(e.text(n));
        if (g == "UM" || g == "ALPHA" || g == "TREF" || is_real_text(g)) break;
        r.nodes.push_back(node(e, n, "Gi,j"));
        r.weights.push_back(weight);
        ++count;
      }
      if (count == 0) e.fail(cf + 1, "Gi,1", "at least one grid after the components");
    }
    if (r.nodes.empty()) e.fail(6, "WT1", "at least one group WTi Ci Gi,1 ...");
    if (!unsupported_reason.empty()) {
      unsupported(card, "RBE3", unsupported_reason);
      return;
    }
    for (int node_index : r.nodes)
      if (node_index == r.reference)
        e.fail(4, "REFGRID", "a reference grid that is not also an independent grid",
               std::to_string(grids_[static_cast<std::size_t>(node_index)].id));
    r.where = e.where();
    mesh_.rigid_elements.push_back(std::move(r));
  }

  // --- constraints
  void read_spc1(const Card& card) {
    const Entry e = entry(card);
    const long sid = e.id(2, "SID");
    const std::array<bool, 6> c = e.components(3, "C");
    int stop = 0;
    const std::vector<int> nodes = grid_list(e, 4, stop, /*skip_missing_in_ranges=*/true);
    if (stop <= e.last()) e.fail(stop, "G", "a grid id or THRU");
    if (nodes.empty() && e.blank(4)) e.fail(4, "G1", "at least one grid");
    if (nodes.empty()) warn(e, 4, "selects no GRID of the deck");
    std::vector<int>& set = mesh_.node_sets[fmt::format("SPC1_{}", sid)];
    spc_sets_.insert(sid);
    for (int n : nodes) {
      check_axes(e, 3, "C", n, c);
      set.push_back(n);
      if (options_.spc_set == 0 || options_.spc_set == sid) add_constraint(n, c, e.where());
    }
  }

  // ASET1 / QSET1 / BSET1 / CSET1  C G1 G2 ... (THRU ranges; grids missing inside a range
  // skipped): the grids form the node set "ASET" (etc.; ASET and ASET1 entries add to one set).
  // The components are checked but the set constrains nothing: it only names nodes (interfaces,
  // masters) for the model file.
  void read_dof_set1(const Card& card) {
    const Entry e = entry(card);
    (void)e.components(2, "C");
    int stop = 0;
    const std::vector<int> nodes = grid_list(e, 3, stop, /*skip_missing_in_ranges=*/true);
    if (stop <= e.last()) e.fail(stop, "G", "a grid id or THRU");
    if (nodes.empty() && e.blank(3)) e.fail(3, "G1", "at least one grid");
    if (nodes.empty()) warn(e, 3, "selects no GRID of the deck");
    std::vector<int>& set = mesh_.node_sets[card.name.substr(0, 4)];
    set.insert(set.end(), nodes.begin(), nodes.end());
  }

  // ASET / QSET / BSET / CSET  ID1 C1 ID2 C2 ... (up to four pairs per line).
  void read_dof_set_pairs(const Card& card) {
    const Entry e = entry(card);
    std::vector<int>& set = mesh_.node_sets[card.name];
    if (e.blank(2)) e.fail(2, "ID1", "at least one grid");
    for (int n = 2; n <= e.last(); n += 2) {
      if (e.blank(n) && e.blank(n + 1)) continue;
      const int node_index = node(e, n, "ID");
      (void)e.components(n + 1, "C");
      set.push_back(node_index);
    }
  }

  // Case control SET n: the grids among its ids form the node set "SET_<n>"; ids that are not
  // grids (the set may list elements for output requests) are skipped, and a set without any
  // grid is not made (a warning says so).
  void read_case_set(const CaseSet& set) {
    std::vector<int> nodes;
    long skipped = 0;
    for (const auto& [from, to] : set.ranges) {
      for (auto it = grid_index_.lower_bound(from); it != grid_index_.end() && it->first <= to;
           ++it)
        if (set.except.count(it->first) == 0) nodes.push_back(it->second);
      if (from == to && grid_index_.count(from) == 0) ++skipped;
    }
    const std::string& file = parser_.files_[static_cast<std::size_t>(set.file)];
    if (nodes.empty()) {
      deck_.warnings.push_back(fmt::format(
          "{}:{}: case control SET {} names no GRID of the deck (an element or output set): "
          "no node set made",
          file, set.line, set.id));
      return;
    }
    if (skipped > 0)
      deck_.warnings.push_back(
          fmt::format("{}:{}: case control SET {}: {} ids are not GRIDs and "
                      "are left out of node set SET_{}",
                      file, set.line, set.id, skipped, set.id));
    std::vector<int>& out = mesh_.node_sets[fmt::format("SET_{}", set.id)];
    out.insert(out.end(), nodes.begin(), nodes.end());
  }

  void add_constraint(int node_index, const std::array<bool, 6>& c, const SourceLocation& where) {
    const auto [it, inserted] = constraint_of_node_.emplace(node_index, mesh_.constraints.size());
    if (inserted) {
      solid::Constraint constraint;
      constraint.node = node_index;
      constraint.components = c;
      constraint.where = where;
      mesh_.constraints.push_back(constraint);
      return;
    }
    auto& existing = mesh_.constraints[it->second].components;
    for (std::size_t k = 0; k < 6; ++k) existing[k] = existing[k] || c[k];
  }

  void finish_constraints() {
    for (auto& [name, nodes] : mesh_.node_sets) {
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    }
    if (options_.spc_set != 0 && spc_sets_.count(options_.spc_set) == 0) {
      std::string available;
      for (long sid : spc_sets_) available += (available.empty() ? "" : ", ") + std::to_string(sid);
      throw InputError(
          SourceLocation{mesh_.source, 0, 0}, "NastranOptions.spc_set",
          "the id of an SPC1 set in the deck (" +
              (available.empty() ? std::string("the deck has none") : "sets: " + available) + ")",
          std::to_string(options_.spc_set));
    }
  }

  const NastranOptions& options_;
  NastranDeck& deck_;
  const DeckParser& parser_;
  solid::Mesh& mesh_;
  std::map<long, CoordSystem> coords_;
  std::vector<Grid> grids_;
  std::map<long, int> grid_index_;
  std::map<long, Mat1> mat1_;
  std::map<long, std::pair<long, const Card*>> psolid_;
  std::map<long, Pelas> pelas_;
  std::map<long, SourceLocation> property_ids_;
  std::map<long, SourceLocation> element_ids_;
  std::set<long> materials_used_;
  std::vector<PendingElement> elements_;
  std::set<long> spc_sets_;
  std::map<int, std::size_t> constraint_of_node_;
};

}  // namespace

bool parse_nastran_real(std::string_view text, double& value) {
  std::size_t i = 0;
  std::string normal;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) {
    if (text[i] == '-') normal.push_back('-');
    ++i;
  }
  bool digits = false, dot = false, exponent = false;
  while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.')) {
    if (text[i] == '.') {
      if (dot) return false;
      dot = true;
    } else {
      digits = true;
    }
    normal.push_back(text[i++]);
  }
  if (!digits) return false;
  if (i < text.size()) {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(text[i])));
    if (c == 'E' || c == 'D')
      ++i;
    else if (c != '+' && c != '-')
      return false;
    normal.push_back('e');
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) normal.push_back(text[i++]);
    std::size_t exponent_digits = 0;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) {
      normal.push_back(text[i++]);
      ++exponent_digits;
    }
    if (exponent_digits == 0 || i != text.size()) return false;
    exponent = true;
  }
  if (!dot && !exponent) return false;
  const char* begin = normal.data();
  const char* end = normal.data() + normal.size();
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

NastranDeck parse_nastran(std::string_view text, const std::string& file_name,
                          const NastranOptions& options) {
  NastranDeck deck;
  deck.mesh.source = file_name;
  DeckParser parser(options, deck);
  parser.parse_top(text, file_name);
  DeckBuilder builder(options, deck, parser);
  builder.build();
  return deck;
}

NastranDeck read_nastran(const std::filesystem::path& path, const NastranOptions& options) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw InputError(SourceLocation{path.string(), 0, 0}, "file",
                     "an existing Nastran bulk data file",
                     "'" + path.string() + "' does not exist or is not a file");
  return parse_nastran(read_file(path), path.string(), options);
}

}  // namespace geardyn::meshio
