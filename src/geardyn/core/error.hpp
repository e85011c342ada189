#pragma once
// The error channels of geardyn (see STYLE.md):
//   bad input          -> InputError (file, line, column, key path, expected, found), exit code 2
//   numerical failure  -> NumericalError (analysis, where, what usually helps), exit code 1
//   broken invariant   -> assert / GEARDYN_ASSERT (a bug in geardyn, not in the model)
#include <stdexcept>
#include <string>

namespace geardyn {

/// Where in a model file a value came from. line/column are 1-based; 0 means unknown.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
};

/// Bad input: the message names the file:line:column, the key path (e.g.
/// `shafts[0].elements[2].length`), what was expected and what was found, and optionally a hint
/// ("did you mean ...?").
class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation where, std::string key_path, std::string expected, std::string found,
             std::string hint = {});

  const SourceLocation& where() const { return where_; }
  const std::string& key_path() const { return key_path_; }
  const std::string& expected() const { return expected_; }
  const std::string& found() const { return found_; }
  const std::string& hint() const { return hint_; }

 private:
  SourceLocation where_;
  std::string key_path_, expected_, found_, hint_;
};

/// A numerical failure that makes a result meaningless: a singular matrix, an eigen-solve that
/// did not converge, a time step that diverged. `what()` says which analysis, where and why.
class NumericalError : public std::runtime_error {
 public:
  NumericalError(std::string analysis, std::string message);
  const std::string& analysis() const { return analysis_; }

 private:
  std::string analysis_;
};

}  // namespace geardyn
