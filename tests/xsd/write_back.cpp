// corsa_xodr_write_back IN.xodr OUT.xodr: reads a map and writes it again with Corsa's writer
// (for the XSD check of what the writer produces from maps Corsa did not make itself).

#include <cstdio>
#include <exception>

#include "corsa/xodr/parser.h"
#include "corsa/xodr/writer.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: corsa_xodr_write_back IN.xodr OUT.xodr\n");
    return 2;
  }
  try {
    corsa::Diagnostics diagnostics;
    corsa::xodr::write_xodr(corsa::xodr::parse_xodr(argv[1], diagnostics), argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
