#pragma once

// The internal entities a document's DOCTYPE declares (XML 1.0 §4.2.1, §4.4), expanded before
// tinyxml2 reads the text: tinyxml2 reads no DTD, but every XML processor, validating or not, has
// to expand the general entities declared in the internal subset (ASAM's API tester files declare
// one, `<!DOCTYPE foo [ <!ENTITY myentity "my entity value" > ]>`).

#include <optional>
#include <string>
#include <string_view>

#include "corsa/core/xml_errors.h"

namespace corsa {

/// Expands the general entities the internal subset of `xml`'s DOCTYPE declares: `expanded` gets
/// the text with the subset blanked (its brackets included, its line breaks kept) and every
/// `&name;` of a declared entity, outside comments, CDATA sections and processing instructions,
/// replaced by its value, whose quotes, tabs and line breaks are written as references, so that
/// every line keeps its number. `expanded` is left empty when there is no internal subset.
///
/// Read: `<!ENTITY name "value">` (or 'value') with a value holding no reference or markup, the
/// first of two declarations of one name binding (§4.2); comments, processing instructions and
/// `<!ELEMENT>`/`<!NOTATION>` declarations, which change no content, are skipped. Anything else
/// is the returned problem at its line: a parameter or external entity, an entity value holding a
/// reference (entities referring to entities could multiply the text without bound), an
/// `<!ATTLIST>` (its defaults would add attributes), an unclosed subset, or an expansion growing
/// the text by more than 16 MiB.
std::optional<XmlTextProblem> expand_internal_entities(std::string_view xml, std::string& expanded);

}  // namespace corsa
