#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

#include "../test_support.hpp"
#include "mfree/io/run_summary.hpp"

using namespace mfree;

TEST_CASE("run summary: JSON with escaped text, null for non-finite numbers, stage calls", "[io]") {
  mfree::testing::ScratchFolder folder("summary", false);
  StageTimer timer;
  for (int i = 0; i < 3; ++i) timer.time("step", [] {});
  timer.time("set-up", [] {});
  RunSummary s("mpm", "a \"quoted\"\\path.toml");
  s.number("finite", 0.125);
  s.number("nan", std::nan(""));
  s.numbers("list", {1.0, INFINITY});
  s.records("errors", {{{"time", 0.5}, {"u", 2e-3}}});
  s.object("applied", {{"force_x", 1.5}, {"moment", std::nan("")}});
  s.objects("reactions", {{"clamped \"end\"", {{"force_x", -1.5}}}, {"wall", {}}});
  s.stages(timer);
  s.write(folder.path);
  std::ifstream in(folder.path / "summary.json");
  std::stringstream text;
  text << in.rdbuf();
  const std::string json = text.str();
  CHECK_THAT(json, Catch::Contains(R"("scene": "a \"quoted\"\\path.toml")"));
  CHECK_THAT(json, Catch::Contains(R"("finite": 0.125)"));
  CHECK_THAT(json, Catch::Contains(R"("nan": null)"));
  CHECK_THAT(json, Catch::Contains(R"("list": [1, null])"));
  CHECK_THAT(json, Catch::Contains(R"({"time": 0.5, "u": 0.002})"));
  CHECK_THAT(json, Catch::Contains(R"("applied": {"force_x": 1.5, "moment": null})"));
  CHECK_THAT(json, Catch::Contains(R"("reactions": {
    "clamped \"end\"": {"force_x": -1.5},
    "wall": {}
  })"));
  CHECK_THAT(json, Catch::Contains(R"("name": "step", "seconds": )") && Catch::Contains(R"("calls": 3})"));
  CHECK_THAT(json, Catch::Contains(R"("calls": 1})"));
  CHECK(json.find("nan\n") == std::string::npos);
  CHECK(timer.calls() == std::vector<long>{3, 1});
}
