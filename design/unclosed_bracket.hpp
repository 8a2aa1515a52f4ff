#pragma once
// Where a TOML list or inline table that is still open was opened. A parser that meets the next
// line's `[[fiber]]` where a list lacks its `]` reports that line; the user needs the line that
// opened the list.

#include <optional>
#include <string_view>

namespace fibermold {

struct TextPlace {
  int line = 0, column = 0; ///< counted from 1, as an editor counts them
};

struct OpenBracket {
  TextPlace at;
  char bracket = '['; ///< '[' (a list) or '{' (an inline table)
};

/// The innermost `[` or `{` of `text` not closed before `before` (outside strings and comments),
/// or nothing where every bracket before it is closed. A table header (`[mold]`, `[[fiber]]`) closes
/// on its own line and so never counts.
std::optional<OpenBracket> unclosed_bracket(std::string_view text, TextPlace before);

} // namespace fibermold
