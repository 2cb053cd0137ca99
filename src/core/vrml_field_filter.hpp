#pragma once
// The lenient pass of the VRML / Inventor reader: removing fields that Coin does not know from the
// file's text, so that a file written with vendor extensions (castle's `mirror`, MGF's `reflSpecular`)
// can still be read. Works on tokens, not lines: comments and strings are respected and a field's
// value may be a number list, a string, an enum, an [array] or a whole node.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace palpate::detail {

// Blanks out (with spaces, keeping newlines so that line numbers stay true) every occurrence of the
// field `field` with its value inside nodes whose type is one of `node_types`. Returns how many
// occurrences it removed.
std::size_t remove_vrml_field(std::string& text, std::string_view field,
                              const std::vector<std::string>& node_types);

}  // namespace palpate::detail
