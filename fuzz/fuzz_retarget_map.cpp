// Fuzzes the retargeting-map reader (`myoshell rig --map`, fit/retarget_map.h), without and with a
// list of known muscles. A map that reads has each ARKit name once; activations in [0, 1] ([-1, 1]
// for a corrective, whose total with its base is in [0, 1]); unreachable shapes with a reason and no
// activations; and written back it reads the same again.
#include <cmath>
#include <set>

#include "fuzz_common.h"
#include "myoshell/core/errors.h"
#include "myoshell/fit/arkit_names.h"
#include "myoshell/fit/retarget_map.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = myo::fuzz::text(data, size);
  const std::vector<std::string> none, some = {"zygomaticus_major_left", "a", "b"};
  for (const std::vector<std::string>* muscles : {&none, &some}) {
    myo::RetargetMap map;
    try {
      map = myo::parseRetargetMap(text, "fuzz_map.json", *muscles);
    } catch (const myo::InputError&) {
      continue;
    }
    FUZZ_EXPECT(!map.shapes.empty(), "at least one shape");
    std::set<std::string> names;
    for (const myo::RetargetShape& s : map.shapes) {
      FUZZ_EXPECT(myo::findArkitName(s.name) == s.name, "stored in ARKit's spelling");
      FUZZ_EXPECT(names.insert(s.name).second, "each name once");
      FUZZ_EXPECT(s.reachable == s.reason.empty(), "a reason exactly for the unreachable");
      if (!s.reachable) FUZZ_EXPECT(s.activations.empty() && s.jaw.empty() && s.correctiveOf.empty(), "nothing to play");
      const double lo = s.correctiveOf.empty() ? 0.0 : -1.0;
      for (const auto& [muscle, v] : s.activations) {
        FUZZ_EXPECT(v >= lo && v <= 1.0, "activation in range");
        if (!muscles->empty()) FUZZ_EXPECT(std::set<std::string>(muscles->begin(), muscles->end()).count(muscle), "known muscle");
      }
      for (const auto& [dof, v] : s.jaw) FUZZ_EXPECT(std::isfinite(v), "finite jaw value");
      if (!s.correctiveOf.empty())
        for (const auto& [muscle, v] : map.totalActivations(s)) FUZZ_EXPECT(v >= -1e-9 && v <= 1.0 + 1e-9, "total in [0, 1]");
    }
    const std::string again = myo::serialiseRetargetMap(map);
    const myo::RetargetMap back = myo::parseRetargetMap(again, "again.json", *muscles);
    FUZZ_EXPECT(myo::serialiseRetargetMap(back) == again, "round trip");
  }
  return 0;
}
