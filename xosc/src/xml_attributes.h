#pragma once

// Internal: attributes written twice in one start tag. XML 1.0 §3.1 (Unique Att Spec) makes such a
// file not well-formed, and tinyxml2 refuses it; esmini's reader (pugixml) keeps both and reads
// the first, so esmini's examples carry such tags (acc-toggle). The loader reads the first too.

#include <string>
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

/// Blanks (with spaces, keeping line breaks) an XML declaration `<?xml ...?>` that follows
/// only white space and comments but does not open `text`; returns its line, 0 when there is
/// no such declaration (none, one at the very start, or one after other content).
int blank_late_declaration(std::string& text);

}  // namespace corsa::xosc
