// Writes the fuzz_web_face seeds (fuzz/web_face_seeds.h) at the format's current version:
//   build/bin/write_web_face_seeds fuzz/corpus/fuzz_web_face
// Run it after a change to the format (WebFaceFile.TheFuzzSeedsAreAtTheCurrentFormat says when).
#include <iostream>

#include "myoshell/core/errors.h"
#include "web_face_seeds.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: write_web_face_seeds DIR\n";
    return 2;
  }
  try {
    for (const myo::fuzz::WebFaceSeed& s : myo::fuzz::webFaceSeeds()) {
      const std::string path = std::string(argv[1]) + "/current_" + s.name + ".myoweb";
      myo::writeWebFaceFile(path, s.muscles, myo::fuzz::webFaceSeedKey(), myo::fuzz::webFaceSeedBasis(), s.takes, s.facs);
      std::cout << path << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "write_web_face_seeds: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
