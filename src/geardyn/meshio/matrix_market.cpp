#include "geardyn/meshio/matrix_market.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <unordered_set>

#include "geardyn/core/text.hpp"

namespace geardyn::meshio {
namespace {

namespace fs = std::filesystem;

struct Token {
  std::string_view text;
  int column = 0;
};

std::vector<Token> tokens_of(std::string_view line) {
  std::vector<Token> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < line.size() && !(line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    if (i > start) out.push_back(Token{line.substr(start, i - start), static_cast<int>(start) + 1});
  }
  return out;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::vector<std::string_view> split_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view l = text.substr(start, end - start);
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    lines.push_back(l);
    start = end + 1;
  }
  return lines;
}

bool parse_long(std::string_view t, long long& v) {
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  return !t.empty() && ec == std::errc() && ptr == t.data() + t.size();
}

bool parse_double(std::string_view t, double& v) {
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  if (t.empty()) return false;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  return ec == std::errc() && ptr == t.data() + t.size();
}

// The whole file; InputError when it does not exist or cannot be read.
std::string read_existing_file(const fs::path& path, const char* what) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw InputError(SourceLocation{path.string(), 0, 0}, "file",
                     fmt::format("an existing {}", what),
                     "'" + path.string() + "' does not exist or is not a file");
  return read_file(path);
}

}  // namespace

namespace {

// Locates a diagnostic at a 0-based line and a 1-based column of the file.
struct Locator {
  const std::string& file;
  SourceLocation operator()(std::size_t line, int column) const {
    return SourceLocation{file, static_cast<int>(line) + 1, column};
  }
};

struct Header {
  bool coordinate = true;
  bool symmetric = false;
};

// Header: %%MatrixMarket matrix <format> <field> <symmetry>
Header parse_header(const std::vector<std::string_view>& lines, const Locator& at) {
  const std::vector<Token> header = tokens_of(lines[0]);
  if (header.empty() || lower(header[0].text) != "%%matrixmarket")
    throw InputError(at(0, 1), "header",
                     "'%%MatrixMarket matrix coordinate real general' or similar",
                     "'" + shorten(lines[0], 60) + "'");
  const auto header_word = [&](std::size_t k, const char* key,
                               std::initializer_list<const char*> allowed) {
    const std::string word = k < header.size() ? lower(header[k].text) : std::string();
    for (const char* a : allowed)
      if (word == a) return word;
    std::string list;
    for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    throw InputError(
        at(0, k < header.size() ? header[k].column : static_cast<int>(lines[0].size()) + 1),
        fmt::format("header.{}", key), "one of: " + list,
        word.empty() ? "nothing" : "'" + word + "'",
        "geardyn reads real matrices (coordinate or array, general or symmetric)");
  };
  (void)header_word(1, "object", {"matrix"});
  const bool coordinate = header_word(2, "format", {"coordinate", "array"}) == "coordinate";
  (void)header_word(3, "field", {"real", "integer"});
  const bool symmetric = header_word(4, "symmetry", {"general", "symmetric"}) == "symmetric";
  if (header.size() > 5)
    throw InputError(at(0, header[5].column), "header", "5 words",
                     fmt::format("{}", header.size()));
  return Header{coordinate, symmetric};
}

// The size line at lines[l]: the order n and the number of entries the file must hold.
struct SizeLine {
  long long n = 0;
  long long expected = 0;
};

SizeLine parse_size_line(const std::vector<std::string_view>& lines, std::size_t l, const Header& h,
                         const Locator& at) {
  const bool coordinate = h.coordinate, symmetric = h.symmetric;
  const std::vector<Token> size = tokens_of(lines[l]);
  const std::size_t size_tokens = coordinate ? 3 : 2;
  if (size.size() != size_tokens)
    throw InputError(
        at(l, 1), "size",
        coordinate ? "three integers: rows columns entries" : "two integers: rows columns",
        fmt::format("{} values", size.size()));
  long long dims[3] = {0, 0, 0};
  for (std::size_t k = 0; k < size_tokens; ++k)
    if (!parse_long(size[k].text, dims[k]) || dims[k] < 0 || (k < 2 && dims[k] == 0))
      throw InputError(at(l, size[k].column),
                       k == 0   ? "size.rows"
                       : k == 1 ? "size.columns"
                                : "size.entries",
                       k < 2 ? "a positive integer" : "an integer >= 0",
                       "'" + std::string(size[k].text) + "'");
  if (dims[0] != dims[1])
    throw InputError(at(l, size[1].column), "size.columns",
                     fmt::format("a square matrix ({} columns)", dims[0]), std::to_string(dims[1]));
  constexpr long long kMaxRows = 100'000'000;
  if (dims[0] > kMaxRows)
    throw InputError(at(l, size[0].column), "size.rows", fmt::format("at most {} rows", kMaxRows),
                     std::to_string(dims[0]));
  const long long n = dims[0];
  const long long expected = coordinate ? dims[2] : (symmetric ? n * (n + 1) / 2 : n * n);
  if (coordinate && (symmetric ? dims[2] > n * (n + 1) / 2 : dims[2] > n * n))
    throw InputError(
        at(l, size[2].column), "size.entries",
        fmt::format("at most {} entries for a {} {}x{} matrix", symmetric ? n * (n + 1) / 2 : n * n,
                    symmetric ? "symmetric" : "general", n, n),
        std::to_string(dims[2]));
  return SizeLine{n, expected};
}

// The entries from lines[l] on, as triplets (both triangles of a symmetric matrix).
std::vector<Eigen::Triplet<double>> read_entries(std::string_view text,
                                                 const std::vector<std::string_view>& lines,
                                                 std::size_t l, const Header& h, const SizeLine& sl,
                                                 const Locator& at,
                                                 std::vector<SourceLocation>& diagonal) {
  const bool coordinate = h.coordinate, symmetric = h.symmetric;
  const long long n = sl.n, expected = sl.expected;
  std::vector<Eigen::Triplet<double>> triplets;
  // Reserve by what the file can hold, not by what its size line claims.
  const long long room = coordinate ? static_cast<long long>(lines.size() - l)
                                    : static_cast<long long>(text.size() / 2 + 1);
  triplets.reserve(static_cast<std::size_t>(std::min(expected, room)) * (symmetric ? 2 : 1));
  std::unordered_set<long long> seen;
  long long count = 0;
  long long array_row = 0, array_column = 0;  // next position of an array file
  const auto value_of = [&](const Token& t, std::size_t line) {
    double v = 0;
    if (!parse_double(t.text, v) || !std::isfinite(v))
      throw InputError(at(line, t.column), "entry.value", "a finite real number",
                       "'" + std::string(t.text) + "'");
    return v;
  };
  for (; l < lines.size(); ++l) {
    const std::vector<Token> t = tokens_of(lines[l]);
    if (t.empty() || t[0].text.front() == '%') continue;
    if (count >= expected)
      throw InputError(at(l, t[0].column), "entry",
                       fmt::format("{} entries (as the size line says)", expected), "more entries");
    if (coordinate) {
      if (t.size() != 3)
        throw InputError(at(l, 1), "entry", "three values: row column value",
                         fmt::format("{} values", t.size()));
      long long ij[2] = {0, 0};
      for (int k = 0; k < 2; ++k)
        if (!parse_long(t[static_cast<std::size_t>(k)].text, ij[k]) || ij[k] < 1 || ij[k] > n)
          throw InputError(at(l, t[static_cast<std::size_t>(k)].column),
                           k == 0 ? "entry.row" : "entry.column",
                           fmt::format("an index in 1..{}", n),
                           "'" + std::string(t[static_cast<std::size_t>(k)].text) + "'");
      if (symmetric && ij[0] < ij[1])
        throw InputError(at(l, t[0].column), "entry.row",
                         "row >= column (a symmetric file lists the lower triangle)",
                         fmt::format("({}, {})", ij[0], ij[1]));
      const double v = value_of(t[2], l);
      if (!seen.insert((ij[0] - 1) * n + (ij[1] - 1)).second)
        throw InputError(at(l, t[0].column), "entry", "each (row, column) once",
                         fmt::format("a second entry ({}, {})", ij[0], ij[1]));
      const int i = static_cast<int>(ij[0] - 1), j = static_cast<int>(ij[1] - 1);
      if (i == j) diagonal[static_cast<std::size_t>(i)] = at(l, t[0].column);
      triplets.emplace_back(i, j, v);
      if (symmetric && i != j) triplets.emplace_back(j, i, v);
      ++count;
    } else {
      for (const Token& token : t) {
        if (count >= expected)
          throw InputError(at(l, token.column), "entry",
                           fmt::format("{} entries (as the size line says)", expected),
                           "more entries");
        const double v = value_of(token, l);
        const int i = static_cast<int>(array_row), j = static_cast<int>(array_column);
        if (i == j) diagonal[static_cast<std::size_t>(i)] = at(l, token.column);
        if (v != 0.0) {
          triplets.emplace_back(i, j, v);
          if (symmetric && i != j) triplets.emplace_back(j, i, v);
        }
        ++count;
        if (++array_row == n) {
          ++array_column;
          array_row = symmetric ? array_column : 0;
        }
      }
    }
  }
  if (count < expected)
    throw InputError(at(lines.size() - 1, 0), "entry",
                     fmt::format("{} entries (as the size line says)", expected),
                     fmt::format("{} before the end of the file", count));
  return triplets;
}

}  // namespace

MatrixMarketMatrix parse_matrix_market(std::string_view text, const std::string& file) {
  const std::vector<std::string_view> lines = split_lines(text);
  const Locator at{file};
  if (lines.empty())
    throw InputError(at(0, 1), "header", "a Matrix Market header line", "an empty file");
  const Header h = parse_header(lines, at);
  std::size_t l = 1;
  const auto skip_comments = [&] {
    while (l < lines.size()) {
      const std::vector<Token> t = tokens_of(lines[l]);
      if (!t.empty() && t[0].text.front() != '%') return;
      ++l;
    }
  };
  skip_comments();
  if (l >= lines.size())
    throw InputError(at(lines.size() - 1, 0), "size", "a size line (rows columns [entries])",
                     "end of file");
  const SizeLine sl = parse_size_line(lines, l, h, at);
  MatrixMarketMatrix result;
  result.symmetric = h.symmetric;
  result.size_line = at(l, 1);
  ++l;

  result.diagonal.assign(static_cast<std::size_t>(sl.n), SourceLocation{file, 0, 0});
  const std::vector<Eigen::Triplet<double>> triplets =
      read_entries(text, lines, l, h, sl, at, result.diagonal);
  result.matrix.resize(static_cast<Eigen::Index>(sl.n), static_cast<Eigen::Index>(sl.n));
  result.matrix.setFromTriplets(triplets.begin(), triplets.end());
  result.matrix.makeCompressed();
  return result;
}

MatrixMarketMatrix read_matrix_market(const fs::path& path) {
  return parse_matrix_market(read_existing_file(path, "Matrix Market file"), path.string());
}

std::vector<solid::DofInfo> parse_dof_map_csv(std::string_view text, const std::string& file) {
  const std::vector<std::string_view> lines = split_lines(text);
  const auto at = [&](std::size_t line, int column) {
    return SourceLocation{file, static_cast<int>(line) + 1, column};
  };
  // Fields of one CSV line with their 1-based columns.
  const auto fields_of = [](std::string_view line) {
    std::vector<Token> out;
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = line.find(',', start);
      std::string_view part = line.substr(
          start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
      std::size_t lead = 0;
      while (lead < part.size() && (part[lead] == ' ' || part[lead] == '\t')) ++lead;
      part.remove_prefix(lead);
      while (!part.empty() && (part.back() == ' ' || part.back() == '\t' || part.back() == '\r'))
        part.remove_suffix(1);
      out.push_back(Token{part, static_cast<int>(start + lead) + 1});
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    return out;
  };
  const auto skip = [](std::string_view line) {
    const std::size_t first = line.find_first_not_of(" \t\r");
    return first == std::string_view::npos || line[first] == '#';
  };
  std::size_t l = 0;
  while (l < lines.size() && skip(lines[l])) ++l;
  if (l >= lines.size())
    throw InputError(at(0, 1), "header", "a header line: node_id,component,x,y,z", "an empty file");
  static constexpr std::array<std::string_view, 5> kColumns{"node_id", "component", "x", "y", "z"};
  std::array<int, 5> column_of{-1, -1, -1, -1, -1};
  const std::vector<Token> header = fields_of(lines[l]);
  for (std::size_t k = 0; k < header.size(); ++k) {
    const std::string name = lower(header[k].text);
    const auto it = std::find(kColumns.begin(), kColumns.end(), name);
    if (it == kColumns.end() || column_of[static_cast<std::size_t>(it - kColumns.begin())] >= 0)
      throw InputError(at(l, header[k].column), "header",
                       "the columns node_id, component, x, y, z (each once)",
                       "'" + std::string(header[k].text) + "'");
    column_of[static_cast<std::size_t>(it - kColumns.begin())] = static_cast<int>(k);
  }
  for (std::size_t k = 0; k < kColumns.size(); ++k)
    if (column_of[k] < 0)
      throw InputError(at(l, 1), "header", "the columns node_id, component, x, y, z",
                       fmt::format("no column '{}'", kColumns[k]));
  ++l;
  std::vector<solid::DofInfo> dofs;
  std::map<std::pair<long, int>, int> seen;                  // (node, component) -> line
  std::map<long, std::pair<Eigen::Vector3d, int>> position;  // node -> (x, line)
  for (; l < lines.size(); ++l) {
    if (skip(lines[l])) continue;
    const std::vector<Token> f = fields_of(lines[l]);
    if (f.size() != header.size())
      throw InputError(at(l, 1), "row", fmt::format("{} comma-separated values", header.size()),
                       fmt::format("{}", f.size()));
    const auto field = [&](std::size_t k) { return f[static_cast<std::size_t>(column_of[k])]; };
    solid::DofInfo dof;
    long long id = 0;
    if (!parse_long(field(0).text, id) || id <= 0 || id > std::numeric_limits<long>::max())
      throw InputError(at(l, field(0).column), "node_id", "a positive integer",
                       "'" + std::string(field(0).text) + "'");
    dof.node_id = static_cast<long>(id);
    const std::string c = lower(field(1).text);
    static constexpr std::array<std::string_view, 6> kNames{"ux", "uy", "uz", "rx", "ry", "rz"};
    if (c.size() == 1 && c[0] >= '1' && c[0] <= '6') {
      dof.component = c[0] - '1';
    } else if (const auto it = std::find(kNames.begin(), kNames.end(), c); it != kNames.end()) {
      dof.component = static_cast<int>(it - kNames.begin());
    } else if (c == "q") {
      dof.component = -1;
    } else {
      throw InputError(at(l, field(1).column), "component",
                       "1..6, ux, uy, uz, rx, ry, rz, or q (generalised coordinate)",
                       "'" + std::string(field(1).text) + "'");
    }
    for (std::size_t k = 2; k < 5; ++k) {
      double v = 0;
      if (!parse_double(field(k).text, v) || !std::isfinite(v))
        throw InputError(at(l, field(k).column), std::string(kColumns[k]), "a finite real number",
                         "'" + std::string(field(k).text) + "'");
      dof.x[static_cast<Eigen::Index>(k - 2)] = v;
    }
    const auto [it, inserted] =
        seen.emplace(std::make_pair(dof.node_id, dof.component), static_cast<int>(l) + 1);
    if (!inserted)
      throw InputError(at(l, field(1).column), "component", "each (node_id, component) once",
                       fmt::format("node {} component '{}' again", dof.node_id, field(1).text),
                       fmt::format("first at line {}", it->second));
    if (dof.component >= 0) {
      const auto [p, first] =
          position.emplace(dof.node_id, std::make_pair(dof.x, static_cast<int>(l) + 1));
      if (!first && p->second.first != dof.x)
        throw InputError(
            at(l, field(2).column), "x", "the same position on every row of a node",
            fmt::format("node {} at ({}, {}, {})", dof.node_id, dof.x[0], dof.x[1], dof.x[2]),
            fmt::format("line {} gives ({}, {}, {})", p->second.second, p->second.first[0],
                        p->second.first[1], p->second.first[2]));
    }
    dofs.push_back(dof);
  }
  if (dofs.empty())
    throw InputError(at(lines.size() - 1, 0), "row", "at least one DOF row", "none");
  return dofs;
}

std::vector<solid::DofInfo> read_dof_map_csv(const fs::path& path) {
  return parse_dof_map_csv(read_file(path, "DOF map CSV file"), path.string());
}

namespace {

// Symmetry: |A_ij - A_ji| <= 1e-10 max|A| for every entry. A matrix written by an FE code from
// a symmetric matrix is symmetric to round-off of its arithmetic (1e-16 .. 1e-13 relative for a
// reduced matrix); 1e-10 leaves three orders of margin for that and still refuses every
// transposed, mis-indexed or unsymmetric (e.g. follower-load) matrix, whose asymmetry is O(1).
void check_symmetric(const MatrixMarketMatrix& m, const std::string& name) {
  const Eigen::SparseMatrix<double>& A = m.matrix;
  const Eigen::SparseMatrix<double> At = A.transpose();
  const Eigen::SparseMatrix<double> D = A - At;
  double scale = 0;
  for (int k = 0; k < A.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it)
      scale = std::max(scale, std::abs(it.value()));
  for (int k = 0; k < D.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(D, k); it; ++it)
      if (std::abs(it.value()) > 1e-10 * scale)
        throw InputError(m.size_line, name, "a symmetric matrix (|A_ij - A_ji| <= 1e-10 max|A|)",
                         fmt::format("A({}, {}) = {} but A({}, {}) = {}", it.row() + 1,
                                     it.col() + 1, A.coeff(it.row(), it.col()), it.col() + 1,
                                     it.row() + 1, A.coeff(it.col(), it.row())));
}

// The DOF a matrix row acts on, for messages.
std::string dof_name(const std::vector<solid::DofInfo>& dofs, Eigen::Index row) {
  static constexpr const char* kNames[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  const solid::DofInfo& d = dofs[static_cast<std::size_t>(row)];
  if (d.component < 0 || d.component > 5)
    return fmt::format("generalised coordinate {}", d.node_id);
  return fmt::format("node {} {}", d.node_id, kNames[d.component]);
}

// Diagonal entries: a mass matrix is positive definite, so every M_ii > 0 (the kinetic energy of
// a unit motion of DOF i); a stiffness matrix is positive semi-definite, so every K_ii >= 0 (the
// strain energy of a unit displacement of DOF i). A wrong sign is located at its line.
void check_diagonal(const MatrixMarketMatrix& m, const std::string& name, bool positive,
                    const std::vector<solid::DofInfo>& dofs) {
  const Eigen::VectorXd d = m.matrix.diagonal();
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    if (positive ? d(i) > 0 : d(i) >= 0) continue;
    const SourceLocation& where = m.diagonal[static_cast<std::size_t>(i)];
    throw InputError(
        where.line > 0 ? where : m.size_line, name,
        positive ? "a positive diagonal (a mass matrix is positive definite: every DOF has mass)"
                 : "a non-negative diagonal (a stiffness matrix is positive semi-definite)",
        fmt::format("{}({}, {}) = {}{} on {}", name, i + 1, i + 1, d(i),
                    where.line > 0 ? "" : " (no entry)", dof_name(dofs, i)),
        positive ? "give every DOF of the DOF map its mass (a massless DOF must be condensed out "
                   "before export)"
                 : "export the stiffness matrix with its sign and units unchanged");
  }
}

}  // namespace

ExternalMatrices read_matrix_market_component(const fs::path& path_K, const fs::path& path_M,
                                              const fs::path& path_dofmap) {
  const MatrixMarketMatrix K = read_matrix_market(path_K);
  const MatrixMarketMatrix M = read_matrix_market(path_M);
  std::vector<solid::DofInfo> dofs = read_dof_map_csv(path_dofmap);
  if (M.matrix.rows() != K.matrix.rows())
    throw InputError(M.size_line, "size.rows",
                     fmt::format("the size of K ({} rows, {})", K.matrix.rows(), path_K.string()),
                     std::to_string(M.matrix.rows()));
  if (static_cast<Eigen::Index>(dofs.size()) != K.matrix.rows())
    throw InputError(SourceLocation{path_dofmap.string(), 0, 0}, "rows",
                     fmt::format("one DOF row per row of K and M ({})", K.matrix.rows()),
                     fmt::format("{} DOF rows", dofs.size()));
  check_symmetric(K, "K");
  check_symmetric(M, "M");
  check_diagonal(M, "M", true, dofs);
  check_diagonal(K, "K", false, dofs);
  ExternalMatrices out;
  out.K = K.matrix;
  out.M = M.matrix;
  out.dofs = std::move(dofs);
  return out;
}

void write_matrix_market(const fs::path& path, const Eigen::SparseMatrix<double>& A,
                         bool symmetric) {
  if (A.rows() != A.cols() && symmetric)
    throw std::invalid_argument(fmt::format(
        "write_matrix_market: a symmetric matrix must be square ({}x{})", A.rows(), A.cols()));
  std::string out = fmt::format("%%MatrixMarket matrix coordinate real {}\n% written by geardyn\n",
                                symmetric ? "symmetric" : "general");
  std::string body;
  long long count = 0;
  double scale = 0;
  for (int k = 0; k < A.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it)
      scale = std::max(scale, std::abs(it.value()));
  for (int k = 0; k < A.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
      if (symmetric) {
        if (std::abs(it.value() - A.coeff(it.col(), it.row())) > 1e-12 * scale)
          throw std::invalid_argument(fmt::format(
              "write_matrix_market: matrix is not symmetric: A({}, {}) = {}, A({}, {}) = {}",
              it.row() + 1, it.col() + 1, it.value(), it.col() + 1, it.row() + 1,
              A.coeff(it.col(), it.row())));
        if (it.row() < it.col()) continue;
      }
      body += fmt::format("{} {} {}\n", it.row() + 1, it.col() + 1, it.value());
      ++count;
    }
  }
  out += fmt::format("{} {} {}\n", A.rows(), A.cols(), count);
  out += body;
  std::ofstream file(path, std::ios::binary);
  if (!file) throw std::runtime_error(fmt::format("cannot create '{}'", path.string()));
  file << out;
  if (!file) throw std::runtime_error(fmt::format("cannot write '{}'", path.string()));
}

void write_dof_map_csv(const fs::path& path, const std::vector<solid::DofInfo>& dofs) {
  std::string out = "node_id,component,x,y,z\n";
  for (const auto& d : dofs)
    out += fmt::format("{},{},{},{},{}\n", d.node_id,
                       d.component < 0 ? std::string("q") : std::to_string(d.component + 1),
                       d.x.x(), d.x.y(), d.x.z());
  std::ofstream file(path, std::ios::binary);
  if (!file) throw std::runtime_error(fmt::format("cannot create '{}'", path.string()));
  file << out;
  if (!file) throw std::runtime_error(fmt::format("cannot write '{}'", path.string()));
}

}  // namespace geardyn::meshio
