#include <catch2/catch.hpp>
#include <fstream>
#include <functional>

#include "mfree/core/error.hpp"
#include "mfree/io/scene_reader.hpp"
#include "../test_support.hpp"

using namespace mfree;

namespace {
std::string error_of(const std::string& text, const std::function<void(const SceneTable&)>& read) {
  try {
    read(Scene::parse(text, "scene.toml").root());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("scene reader: typed values, and errors that name the key and position", "[io]") {
  const auto read = [](const SceneTable& root) {
    const SceneTable m = root.table("material");
    (void)m.number("E", 0.0, 1e300);
    (void)m.number_or("nu", 0.3, -1.0, 0.5);
    m.finish();
    root.finish();
  };
  CHECK(error_of("[material]\nE = 3e7\nnu = 0.3\n", read).empty());
  CHECK_THAT(error_of("[material]\nE = -3e7\n", read),
             Catch::Contains("scene.toml:2:") && Catch::Contains("material.E") &&
                 Catch::Contains("out of range"));
  CHECK_THAT(error_of("[material]\nE = 'big'\n", read),
             Catch::Contains("material.E") && Catch::Contains("expected a number"));
  CHECK_THAT(error_of("[material]\nnu = 0.3\n", read),
             Catch::Contains("material.E") && Catch::Contains("missing"));
  CHECK_THAT(error_of("[material]\nE = 1.0\nEE = 2.0\n", read),
             Catch::Contains("scene.toml:3:") && Catch::Contains("material.EE") &&
                 Catch::Contains("unknown key"));
  CHECK_THAT(error_of("[material]\nE = 1.0\n[solver]\n", read),
             Catch::Contains("'solver'") && Catch::Contains("unknown key"));
  CHECK_THAT(error_of("[material\nE = 1.0\n", read), Catch::Contains("scene.toml:1:"));
}

TEST_CASE("scene reader: choices and arrays", "[io]") {
  const auto read = [](const SceneTable& root) {
    (void)root.choices("clouds", {"lattice", "random"});
    (void)root.numbers("lo", 2, -10, 10);
    root.finish();
  };
  CHECK(error_of("clouds = ['lattice']\nlo = [0, 1]\n", read).empty());
  CHECK_THAT(error_of("clouds = ['lattice', 'lattice']\nlo = [0, 1]\n", read), Catch::Contains("twice"));
  CHECK_THAT(error_of("clouds = ['grid']\nlo = [0, 1]\n", read),
             Catch::Contains("'grid' is not one of: lattice, random"));
  CHECK_THAT(error_of("clouds = ['lattice']\nlo = [0, 1, 2]\n", read),
             Catch::Contains("array of 2 numbers"));
  CHECK_THROWS_WITH(Scene::load("/nonexistent/scene.toml"),
                    Catch::Contains("/nonexistent/scene.toml") && Catch::Contains("cannot open"));
}

TEST_CASE("scene overrides: --set replaces, adds, and is named in errors", "[io]") {
  mfree::testing::ScratchFolder folder("overrides");
  const std::filesystem::path file = folder.path / "scene.toml";
  {
    std::ofstream out(file);
    out << "[material]\nE = 3e7\n[mpm]\nmethod = \"bspline\"\n";
  }
  const Scene scene = Scene::load(file, {"material.E=2.5e7", "material.nu=0.25", "mpm.method=cpdi",
                                         "study.cells=[8, 16]"});
  const SceneTable root = scene.root();
  CHECK(root.table("material").number("E", 0, 1e300) == 2.5e7);
  CHECK(root.table("material").number("nu", 0, 0.5) == 0.25);
  CHECK(root.table("mpm").string("method") == "cpdi");
  CHECK(root.table("study").numbers("cells", 0, 1, 100) == std::vector<double>{8, 16});

  const auto read_e = [&](const std::vector<std::string>& o) {
    return mfree::testing::message_of<InputError>([&] {
      (void)Scene::load(file, o).root().table("material").number("E", 0.0, 1e300);
    });
  };
  CHECK_THAT(read_e({"material.E=-1"}), Catch::Contains("--set material.E=-1") && Catch::Contains("out of range"));
  CHECK_THAT(read_e({"material.E.x=1"}), Catch::Contains("'material.E' is not a section"));
  CHECK_THAT(read_e({"material"}), Catch::Contains("expected section.key=value"));
}

TEST_CASE("scene overrides: --set reaches a [[table]] by its name or its place", "[io]") {
  mfree::testing::ScratchFolder folder("overrides_lists");
  const std::filesystem::path file = folder.path / "scene.toml";
  {
    std::ofstream out(file);
    out << "[[material]]\nname = \"steel\"\nE = 2e11\n[[material]]\nname = \"resin\"\nE = 3e9\n"
           "[[boundary]]\nname = \"hold y\"\nvalue = [0, 0]\n";
  }
  const Scene scene =
      Scene::load(file, {"material.resin.E=4e9", "material[0].density=7800", "boundary[0].value=[0, 1]"});
  const std::vector<SceneTable> laws = scene.root().tables("material");
  CHECK(laws[0].number("E", 0, 1e300) == 2e11);
  CHECK(laws[0].number("density", 0, 1e300) == 7800);
  CHECK(laws[1].number("E", 0, 1e300) == 4e9);
  CHECK(scene.root().tables("boundary")[0].numbers("value", 2, -1, 1) == std::vector<double>{0, 1});
  // A value out of range names the override, as for a section.
  CHECK_THAT(
      mfree::testing::message_of<InputError>([&] {
        (void)Scene::load(file, {"material.resin.E=-1"}).root().tables("material")[1].number("E", 0, 1e300);
      }),
      Catch::Contains("--set material.resin.E=-1"));

  const auto load_error = [&](const std::string& o) {
    return mfree::testing::message_of<InputError>([&] { (void)Scene::load(file, {o}); });
  };
  CHECK_THAT(load_error("material.E=1"), Catch::Contains("'material' is a list of tables") &&
                                             Catch::Contains("material.<name>.E") &&
                                             Catch::Contains("steel, resin"));
  CHECK_THAT(load_error("material.glass.E=1"), Catch::Contains("no [[material]] table is named 'glass'"));
  CHECK_THAT(load_error("material[2].E=1"),
             Catch::Contains("2 [[material]] table(s), numbered from 0: there is no 2"));
  CHECK_THAT(load_error("material[x].E=1"), Catch::Contains("'material[x]' is not a place"));
  CHECK_THAT(load_error("mpm[0].cells=1"), Catch::Contains("the scene has no [[mpm]] tables"));
  CHECK_THAT(load_error("material.steel.E.x=1"), Catch::Contains("'material.steel.E' is not a section"));
}
