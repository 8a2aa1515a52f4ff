#pragma once
// Bad input: an exception that carries where (file, line, column, key) and what is wrong.
// The CLI turns it into exit code 2 (docs/architecture.md, "Rules of the house").

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace fibermold {

/// One problem in an input file: `file:line:column: key: message`.
struct Diagnostic {
  std::filesystem::path file;
  int line = 0;    ///< 1-based; 0 when unknown
  int column = 0;  ///< 1-based; 0 when unknown
  std::string key; ///< e.g. "[mold].wall"; empty when the problem is not about a key
  std::string message;

  std::string to_string() const;
};

/// One or more problems with the user's input, reported together.
class InputError : public std::runtime_error {
public:
  explicit InputError(std::vector<Diagnostic> diagnostics);
  explicit InputError(Diagnostic diagnostic);

  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

private:
  std::vector<Diagnostic> diagnostics_;
};

} // namespace fibermold
