#include "core/array_file.hpp"

#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "core/atomic_file.hpp"

namespace fibermold {

namespace {
constexpr char kMagic[8] = {'F', 'M', 'A', 'R', 'R', 'A', 'Y', '1'};

std::uint64_t checksum(std::string_view bytes)
{
  std::uint64_t h = 1469598103934665603ull; // FNV-1a
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  return h;
}
} // namespace

void save_array(const std::filesystem::path& path, const std::string& kind, const Eigen::VectorXd& values)
{
  std::string payload(reinterpret_cast<const char*>(values.data()),
                      static_cast<std::size_t>(values.size()) * sizeof(double));
  std::string out(kMagic, sizeof kMagic);
  const std::uint64_t header[3] = {kind.size(), payload.size(), checksum(payload)};
  out.append(reinterpret_cast<const char*>(header), sizeof header);
  out += kind;
  write_file_atomic(path, out + payload);
}

Eigen::VectorXd load_array(const std::filesystem::path& path, const std::string& kind)
{
  const std::string bytes = read_file(path);
  const auto fail = [&](const char* what) { return std::runtime_error(path.string() + ": " + what); };
  std::uint64_t header[3];
  if (bytes.size() < sizeof kMagic + sizeof header || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw fail("not a fibermold array file");
  std::memcpy(header, bytes.data() + sizeof kMagic, sizeof header);
  const std::size_t start = sizeof kMagic + sizeof header;
  if (bytes.size() != start + header[0] + header[1] || header[1] % sizeof(double) != 0)
    throw fail("truncated array file");
  if (bytes.compare(start, header[0], kind) != 0) throw fail(("not a " + kind + " file").c_str());
  const std::string_view payload(bytes.data() + start + header[0], header[1]);
  if (checksum(payload) != header[2]) throw fail("corrupt array file");
  Eigen::VectorXd values(static_cast<Eigen::Index>(header[1] / sizeof(double)));
  std::memcpy(values.data(), payload.data(), payload.size());
  return values;
}

} // namespace fibermold
