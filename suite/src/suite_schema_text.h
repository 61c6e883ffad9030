#pragma once

namespace corsa::suite::detail {

/// The text of schemas/suite.xsd, compiled in at build time.
const char* suite_schema_text();

}  // namespace corsa::suite::detail
