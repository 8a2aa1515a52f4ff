#pragma once
// Words for a POSIX shell: a command that sweep writes into a job script, or that README.txt gives a
// user to copy.

#include <algorithm>
#include <string>
#include <string_view>

namespace fibermold {

/// `word` in single quotes, each ' within it closed, escaped and reopened: the shell reads it back as is.
inline std::string shell_quoted(std::string_view word)
{
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// `word` as it is where a shell reads it so (letters, digits and _./-+:=,@), else shell_quoted.
inline std::string shell_word(std::string_view word)
{
  const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
           std::string_view("_./-+:=,@").find(c) != std::string_view::npos;
  });
  return plain ? std::string(word) : shell_quoted(word);
}

} // namespace fibermold
