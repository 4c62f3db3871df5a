// libFuzzer target: the scene readers. The input is a scene, optionally followed by a line
// "%%" and --set overrides, one per line. Every scene kind is read as `mfree run` and
// `mfree converge` read it (the material-point reader when it has [path], the MPM reader
// when it has [mpm]); a refusal is an mfree::Error.
#include <vector>

#include "fuzz_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/io/elasticity_scene.hpp"
#include "mfree/io/mpm_scene.hpp"
#include "mfree/io/path_scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view all = mfree::fuzz::text(data, size);
  const std::size_t split = all.find("\n%%\n");
  const std::string_view scene = all.substr(0, split);
  std::vector<std::string> overrides;
  if (split != std::string_view::npos) {
    std::string_view rest = all.substr(split + 4);
    while (!rest.empty()) {
      const std::size_t eol = rest.find('\n');
      if (eol != 0) overrides.emplace_back(rest.substr(0, eol));
      if (eol == std::string_view::npos) break;
      rest.remove_prefix(eol + 1);
    }
  }
  const std::filesystem::path file = mfree::fuzz::input_file(
      reinterpret_cast<const std::uint8_t*>(scene.data()), scene.size(), "scene.toml");
  for (const bool study : {false, true}) {
    try {
      if (mfree::is_path_scene(file))
        (void)mfree::read_path_scene(file, overrides);
      else if (mfree::is_mpm_scene(file))
        (void)mfree::read_mpm_scene(file, study, overrides);
      else
        (void)mfree::read_elasticity_scene(file, study, overrides);
    } catch (const mfree::Error&) {
    }
  }
  return 0;
}
