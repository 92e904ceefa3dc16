// Tests: a copy of a CSV file without the columns whose header cell `drop` names (the demo take
// without its jaw units, without its gaze columns, …).
#pragma once

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace myo::test {

inline void copyCsvWithoutColumns(const std::filesystem::path& from, const std::filesystem::path& to,
                                  const std::function<bool(const std::string&)>& drop) {
  std::ifstream in(from);
  std::ofstream out(to);
  std::string line;
  std::vector<bool> keep;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    if (keep.empty())
      for (const std::string& c : cells) keep.push_back(!drop(c));
    std::string row;
    for (size_t i = 0; i < cells.size(); ++i)
      if (keep[i]) row += (row.empty() ? "" : ",") + cells[i];
    out << row << "\n";
  }
}

}  // namespace myo::test
