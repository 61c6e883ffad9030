#include "corsa/suite/junit.h"

#include "corsa/core/strings.h"

namespace corsa::suite {
namespace {

std::string seconds(double value) { return format_fixed(value, 3); }

std::string counts(size_t tests, const SuiteReport& report, double time) {
  return " tests=\"" + std::to_string(tests) + "\" failures=\"" + std::to_string(report.failed) +
         "\" errors=\"" + std::to_string(report.errors) + "\" time=\"" + seconds(time) + "\"";
}

void testcase(const std::string& suite_name, const TestOutcome& outcome, std::string& out) {
  out += "    <testcase name=\"" + xml_escape(outcome.name) + "\" classname=\"" +
         xml_escape(suite_name) + "\" time=\"" + seconds(outcome.run.wall_seconds) + "\"";
  if (outcome.verdict == Verdict::kPassed) {
    out += "/>\n";
    return;
  }
  out += ">\n";
  if (outcome.verdict == Verdict::kError) {
    out += "      <error message=\"" + xml_escape(outcome.error) + "\" type=\"error\">" +
           xml_escape(outcome.error) + "</error>\n";
  } else {
    std::string all;
    for (const auto& failure : outcome.failures) all += failure + "\n";
    out += "      <failure message=\"" + xml_escape(outcome.failures.front()) +
           "\" type=\"expectation\">" + xml_escape(all) + "</failure>\n";
  }
  out += "    </testcase>\n";
}

}  // namespace

std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t' && c != '\r') {
          out += "\xEF\xBF\xBD";  // U+FFFD: XML 1.0 has no other control characters
        } else {
          out += c;
        }
    }
  }
  return out;
}

std::string junit_xml(const Suite& suite, const SuiteReport& report) {
  const size_t tests = report.outcomes.size();
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<testsuites name=\"corsa\"" + counts(tests, report, report.wall_seconds) + ">\n";
  out += "  <testsuite name=\"" + xml_escape(suite.name) + "\"" +
         counts(tests, report, report.wall_seconds) + " skipped=\"0\">\n";
  for (const TestOutcome& outcome : report.outcomes) testcase(suite.name, outcome, out);
  out += "  </testsuite>\n</testsuites>\n";
  return out;
}

}  // namespace corsa::suite
