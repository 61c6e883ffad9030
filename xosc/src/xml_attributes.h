#pragma once

// Internal: attributes written twice in one start tag. XML 1.0 §3.1 (Unique Att Spec) makes such a
// file not well-formed, and tinyxml2 refuses it; esmini's reader (pugixml) keeps both and reads
// the first, so esmini's examples carry such tags (acc-toggle). The loader reads the first too.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace corsa::xosc {

/// One repeat of an attribute that was taken out of the text.
struct RepeatedAttribute {
  int line = 1;           ///< the line of the repeat
  std::string element;    ///< the tag's name
  std::string attribute;  ///< the attribute's name
  std::string kept;       ///< the first value, which stays
  std::string dropped;    ///< the repeat's value, taken out
};

/// Overwrites with blanks every repeat of an attribute within a start tag after its first
/// occurrence (line breaks are kept, so every line number stays), outside comments, CDATA
/// sections, processing instructions and declarations; returns the repeats in document order.
/// A tag too broken to scan ends the scan: the parser's own error then says where.
std::vector<RepeatedAttribute> blank_repeated_attributes(std::string& text);

/// The line of attribute `name` in the start tag that is the `ordinal`-th (from 0) to open on
/// line `tag_line` of `text`, for errors about an attribute of a tag written over several lines
/// (tinyxml2 gives the tag's first line only). Comments, CDATA sections, processing instructions,
/// declarations and quoted values are stepped over. Nothing when the tag or attribute is not
/// there or the text is too broken to scan. It reads the text from its start: for error paths.
std::optional<int> attribute_line(std::string_view text, int tag_line, int ordinal,
                                  std::string_view name);

/// Blanks (with spaces, keeping line breaks) an XML declaration `<?xml ...?>` that follows
/// only white space and comments but does not open `text`; returns its line, 0 when there is
/// no such declaration (none, one at the very start, or one after other content).
int blank_late_declaration(std::string& text);

}  // namespace corsa::xosc
