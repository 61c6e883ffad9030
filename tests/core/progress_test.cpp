#include "corsa/core/progress.h"

#include <catch2/catch.hpp>
#include <cstdio>

TEST_CASE("the progress bar shows fill, percent and ETA", "[core][progress]") {
  const std::string half = corsa::ProgressBar::render("run", 5.0, 10.0, 2.0, 10);
  CHECK(half == "run [#####-----] 50% ETA 2.0s");
  const std::string done = corsa::ProgressBar::render("run", 10.0, 10.0, 3.0, 10);
  CHECK(done == "run [##########] 100% done in 3.00s");
  const std::string empty = corsa::ProgressBar::render("x", 0.0, 0.0, 0.0, 4);
  CHECK(empty == "x [----] 0%");
}

TEST_CASE("the progress bar stays silent when not on a terminal", "[core][progress]") {
  std::FILE* sink = std::tmpfile();
  REQUIRE(sink != nullptr);
  {
    corsa::ProgressBar bar("quiet", 100.0, true, sink);
    CHECK_FALSE(bar.visible());
    for (int i = 0; i < 100; ++i) {
      bar.advance();
    }
  }
  CHECK(std::ftell(sink) == 0);
  std::fclose(sink);
  corsa::ProgressBar disabled("off", 1.0, false);
  CHECK_FALSE(disabled.visible());
}

TEST_CASE("the progress bar can learn its total late, restart and complete", "[core][progress]") {
  CHECK(corsa::ProgressBar::render("run", 10.0, 20.0, 1.0, 10) == "run [#####-----] 50% ETA 1.0s");
  std::FILE* sink = std::tmpfile();
  REQUIRE(sink != nullptr);
  corsa::ProgressBar bar("run", 3600.0, true, sink);  // not a terminal: silent, but it counts
  bar.set_total(20.0);
  bar.update(19.84);
  bar.complete();
  bar.restart("preview video", 21.0);
  bar.update(3.0);
  bar.finish();
  CHECK(std::ftell(sink) == 0);
  std::fclose(sink);
}
