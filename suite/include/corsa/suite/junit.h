#pragma once

// JUnit XML, the report format CI servers read (Jenkins, GitLab, GitHub actions):
//   <testsuites name tests failures errors time>
//     <testsuite name tests failures errors skipped time>
//       <testcase name classname time>
//         <failure message type>every missed expectation, one per line</failure>
//         or <error message type>why the scenario could not run</error>
//       </testcase> ...
// Times are wall-clock seconds (they differ between runs; everything else does not).

#include <string>

#include "corsa/suite/suite.h"
#include "corsa/suite/suite_run.h"

namespace corsa::suite {

std::string junit_xml(const Suite& suite, const SuiteReport& report);

/// Text escaped for XML attribute values and character data (& < > " ' and control characters,
/// which XML 1.0 cannot hold, as U+FFFD).
std::string xml_escape(std::string_view text);

}  // namespace corsa::suite
