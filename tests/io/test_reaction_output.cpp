#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/io/reaction_output.hpp"

using namespace mfree;

namespace {

/// Two parts in balance with the load and the inertia, scaled by s.
Reactions<2> sample(double s, bool inertia) {
  Reactions<2> r;
  r.parts = {{"clamp, left", {Vec2(-1.5 * s, 2.0 * s), 3.0 * s}}, {"wall", {Vec2(0.0, -1.0 * s), -1.0 * s}}};
  r.applied = {Vec2(2.0 * s, -0.5 * s), -1.5 * s};
  if (inertia) r.inertia = Resultant<2>{Vec2(0.5 * s, 0.5 * s), 0.5 * s};
  r.arm = 2.0;
  return r;
}

}  // namespace

TEST_CASE("reaction output: console lines, summary and CSV rows per part, the loads and the balance",
          "[io]") {
  const Reactions<2> r = sample(1.0, true);
  CHECK(r.balance().force.norm() == 0.0);
  CHECK(r.balance().moment == 0.0);
  const std::string lines = reaction_lines(r);
  CHECK_THAT(lines, Catch::Contains("arm X)"));
  CHECK_THAT(lines, Catch::Contains("clamp, left") &&
                        Catch::Contains("R = ( -1.500000e+00,   2.000000e+00), M =   3.000000e+00"));
  CHECK_THAT(lines, Catch::Contains("inertia                M a = (  5.000000e-01,   5.000000e-01)"));
  CHECK_THAT(lines, Catch::Contains("imbalance 0.000e+00 of the largest force, moment 0.000e+00"));

  mfree::testing::ScratchFolder folder("reaction_summary");
  RunSummary summary("dynamics", "scene.toml");
  summarise_reactions(summary, r);
  summary.write(folder.path);
  std::ifstream in(folder.path / "summary.json");
  std::stringstream json;
  json << in.rdbuf();
  CHECK_THAT(json.str(), Catch::Contains(R"("clamp, left": {"force_x": -1.5, "force_y": 2, "moment": 3})"));
  CHECK_THAT(json.str(), Catch::Contains(R"("applied": {"force_x": 2, "force_y": -0.5, "moment": -1.5})"));
  CHECK_THAT(json.str(), Catch::Contains(R"("inertia": {"force_x": 0.5)"));
  CHECK_THAT(json.str(), Catch::Contains(R"("imbalance": 0,)"));

  ReactionTable<2> table("time", {"clamp, left", "wall"}, true);
  table.add(0, 0.0, sample(0.0, true));
  table.add(5, 0.25, r);
  const std::string csv = table.csv();
  CHECK_THAT(csv, Catch::StartsWith("step,time,part,rx,ry,moment\n"));
  // The part's comma would split its cell: replaced.
  CHECK_THAT(csv, Catch::Contains("5,0.25,clamp; left,-1.500000000e+00,2.000000000e+00,3.000000000e+00\n"));
  CHECK_THAT(csv, Catch::Contains("5,0.25,inertia,5.000000000e-01,5.000000000e-01,5.000000000e-01\n"));
  CHECK_THAT(csv, Catch::EndsWith("5,0.25,balance,0.000000000e+00,0.000000000e+00,0.000000000e+00\n"));
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 1 + 2 * 5);
}

TEST_CASE(
    "reaction output: a table saved in a checkpoint restores to the same CSV; broken records are refused",
    "[io][checkpoint]") {
  ReactionTable<2> table("time", {"clamp", "wall"}, true);
  for (int step = 0; step <= 6; step += 3) table.add(step, 0.1 * step, sample(0.1 * step + 0.3, true));
  CheckpointState state;
  state.source = "run.checkpoints/step_0000000006/state.bin";
  table.save(state);
  REQUIRE(state.get("reactions").size() == 3 * (2 + 3 * 4));
  ReactionTable<2> again("time", {"clamp", "wall"}, true);
  again.restore(state, 6, 6 * 0.1);  // the time of step 6 as the run takes it
  CHECK(again.csv() == table.csv());

  const auto refusal = [&](std::vector<double> values, long long step, double time) {
    CheckpointState s = state;
    s.put("reactions", std::move(values));
    ReactionTable<2> t("time", {"clamp", "wall"}, true);
    return mfree::testing::message_of<InputError>([&] { t.restore(s, step, time); });
  };
  std::vector<double> v = state.get("reactions");
  CHECK_THAT(refusal(std::vector<double>(v.begin(), v.end() - 1), 6, 6 * 0.1),
             Catch::Contains(
                 "array 'reactions': it holds 41 numbers, not 14 per record (2 essential part(s) and the "
                 "inertia)"));
  CHECK_THAT(refusal(v, 5, 6 * 0.1),
             Catch::Contains("value 28 is 6, not a step after 3 and up to the checkpoint's 5"));
  std::vector<double> repeated = v;
  repeated[14] = 0.0;  // the second record's step, again 0
  CHECK_THAT(refusal(repeated, 6, 6 * 0.1), Catch::Contains("value 14 is 0, not a step after 0"));
  CHECK_THAT(refusal(v, 6, 0.5), Catch::Contains("value 29 is 0.6") &&
                                     Catch::Contains("not a time of the run so far (0 to 0.5)"));
  // A table of other parts (another scene) does not fit.
  ReactionTable<2> one("time", {"clamp"}, true);
  CHECK_THAT(mfree::testing::message_of<InputError>([&] { one.restore(state, 6, 6 * 0.1); }),
             Catch::Contains("not 11 per record (1 essential part(s) and the inertia)"));
}
