#pragma once
// Plain text for a reader: a paragraph broken into lines at spaces, as README.txt gives it.

#include <string>

namespace fibermold {

/// `text` broken into lines of at most 100 characters (code points) at spaces, the first line
/// starting with `first`, the others with `rest`; ends with a newline.
std::string wrapped(const std::string& text, const std::string& first, const std::string& rest);

} // namespace fibermold
