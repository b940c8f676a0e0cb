#include "sheet.hpp"

#include <cstdlib>

namespace s2sim::pascal {

std::string cell_name(int row, int col) {
  std::string letters;
  for (int c = col; c > 0; c = (c - 1) / 26)
    letters.insert(letters.begin(), static_cast<char>('A' + (c - 1) % 26));
  return letters + std::to_string(row);
}

double Sheet::parse_number(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return 0;
  const auto last = text.find_last_not_of(" \t\r\n");
  const std::string t = text.substr(first, last - first + 1);
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);  // the C locale: '.' as SimTwo forces
  return end == t.c_str() + t.size() ? v : 0.0;
}

Sheet::Cell& Sheet::set(int row, int col, const std::string& text) {
  Cell& cell = cells_[{row, col}];
  if (cell.text == text && !(text.empty() && cell.kind != Kind::text)) return cell;
  cell.text = text;
  const auto first = text.find_first_not_of(" \t");
  const auto last = text.find_last_not_of(" \t");
  const std::string t = first == std::string::npos ? "" : text.substr(first, last - first + 1);
  if (t.size() >= 2 && t.front() == '[' && t.back() == ']') {
    cell.kind = Kind::button;
    cell.value = 0;
  } else if (!t.empty() && t.front() == '=') {
    cell.kind = Kind::formula;  // not evaluated (docs/scripting.md)
    cell.value = 0;
  } else {
    cell.kind = Kind::text;
    cell.value = parse_number(t);
  }
  return cell;
}

Sheet::Cell* Sheet::find(int row, int col) {
  const auto it = cells_.find({row, col});
  return it == cells_.end() ? nullptr : &it->second;
}

}  // namespace s2sim::pascal
