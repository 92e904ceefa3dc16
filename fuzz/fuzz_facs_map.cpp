// Fuzzes the FACS map reader (fit/facs_map.h), without and with a list of known muscles, and plays
// what reads through activationsForAus. A map that reads has each AU once, a positive number, a name,
// the openface flag of OpenFace 2.0's list, weights in [0, 1], only known muscles when a list is
// given, and muscles or a `needs`, never both; every AU at full intensity gives activations in
// [0, 1]; written back it reads the same again.
#include <algorithm>
#include <set>

#include "fuzz_common.h"
#include "myoshell/core/errors.h"
#include "myoshell/fit/facs_map.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = myo::fuzz::text(data, size);
  const std::vector<std::string> none, some = {"zygomaticus_major_left", "procerus", "a", "b"};
  for (const std::vector<std::string>* muscles : {&none, &some}) {
    myo::FacsMap map;
    try {
      map = myo::parseFacsMap(text, "fuzz_facs_map.json", *muscles);
    } catch (const myo::InputError&) {
      continue;
    }
    FUZZ_EXPECT(!map.entries.empty(), "at least one AU");
    const std::set<std::string> known(muscles->begin(), muscles->end());
    const std::vector<int>& openFace = myo::openFaceIntensityAus();
    std::set<int> aus;
    std::set<std::string> driven;
    myo::AuIntensities all;
    for (const myo::FacsEntry& e : map.entries) {
      FUZZ_EXPECT(e.au > 0 && e.au < 1000, "AU number in range");
      FUZZ_EXPECT(aus.insert(e.au).second, "each AU once");
      FUZZ_EXPECT(!e.name.empty(), "a name");
      FUZZ_EXPECT(e.openface == std::binary_search(openFace.begin(), openFace.end(), e.au), "openface agrees");
      FUZZ_EXPECT(e.muscles.empty() != e.needs.empty(), "muscles or needs, not both");
      std::set<std::string> own;
      for (const auto& entry : e.muscles) {
        FUZZ_EXPECT(entry.second >= 0.0 && entry.second <= 1.0, "weight in [0, 1]");
        FUZZ_EXPECT(own.insert(entry.first).second, "each muscle once per AU");
        if (!known.empty()) FUZZ_EXPECT(known.count(entry.first) == 1, "known muscle");
        driven.insert(entry.first);
      }
      all.emplace_back(e.au, 1.0);
    }
    const std::vector<std::string> names(driven.begin(), driven.end());
    const myo::VecX a = myo::activationsForAus(map, all, names);
    FUZZ_EXPECT(a.size() == static_cast<Eigen::Index>(names.size()), "one activation per muscle");
    FUZZ_EXPECT(names.empty() || (a.minCoeff() >= 0.0 && a.maxCoeff() <= 1.0), "activations in [0, 1]");
    const std::string again = myo::serialiseFacsMap(map);
    const myo::FacsMap back = myo::parseFacsMap(again, "again.json", *muscles);
    FUZZ_EXPECT(myo::serialiseFacsMap(back) == again, "round trip");
  }
  return 0;
}
