#include "core/input_error.hpp"

namespace fibermold {

std::string Diagnostic::to_string() const
{
  std::string out = file.empty() ? std::string("fibermold") : file.string();
  if (line > 0) {
    out.append(1, ':').append(std::to_string(line));
    if (column > 0) out.append(1, ':').append(std::to_string(column));
  }
  out.append(": ");
  if (!key.empty()) out.append(key).append(": ");
  return out.append(message);
}

namespace {
std::string join(const std::vector<Diagnostic>& diagnostics)
{
  std::string out;
  for (const Diagnostic& d : diagnostics) {
    if (!out.empty()) out += "\n";
    out += d.to_string();
  }
  return out;
}
} // namespace

InputError::InputError(std::vector<Diagnostic> diagnostics)
    : std::runtime_error(join(diagnostics)), diagnostics_(std::move(diagnostics))
{
}

InputError::InputError(Diagnostic diagnostic) : InputError(std::vector<Diagnostic>{std::move(diagnostic)}) {}

} // namespace fibermold
