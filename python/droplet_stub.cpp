// Writes the Python stub _core.pyi from its template: the line `@DROPLET_PARAMS_FIELDS@` becomes
// DropletParams' attributes and its __init__'s keywords, one per field of visit_droplet_fields, in
// that order, each with its Python type (a whole number int, a real float, a name str). So a new
// droplet parameter reaches editors and type checkers with no edit of the stub.
//   droplet_stub TEMPLATE OUTPUT
// The output is written to a temporary file beside it and renamed, so a build stopped midway
// leaves the old stub or the new one, never half of one.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <softdrop/droplet.hpp>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "cli/columns.hpp"

namespace {

using softdrop::DropletField;
using softdrop::DropletParams;

template <class T>
const char* python_type() {
  if constexpr (std::is_same_v<T, bool>)
    return "bool";
  else if constexpr (std::is_integral_v<T>)
    return "int";
  else if constexpr (std::is_floating_point_v<T>)
    return "float";
  else {
    static_assert(std::is_enum_v<T>, "a droplet field is a number or an enum (a name in Python)");
    return "str";
  }
}

// The class body's lines for the fields, indented as `indent` (the marker's): the attributes, then
// __init__ with every field a keyword, in lines of at most 120 columns as the rest of the stub.
std::string fields_block(const std::string& indent) {
  std::vector<std::string> names, types;
  DropletParams defaults;
  softdrop::visit_droplet_fields(
      [&](const DropletField& field, const auto& value) {
        names.push_back(softdrop::cli::column_name(field.key));  // the module's attribute name (module.cpp)
        types.emplace_back(python_type<std::decay_t<decltype(value)>>());
      },
      defaults);
  std::ostringstream out;
  for (std::size_t i = 0; i < names.size(); ++i) out << indent << names[i] << ": " << types[i] << "\n";
  const std::string head = indent + "def __init__(self, *, ";
  const std::string hang(indent.size() + std::string("def __init__(").size(), ' ');  // under `self`
  std::string line = head;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string item = names[i] + ": " + types[i] + " = ..." + (i + 1 < names.size() ? "," : ") -> None: ...");
    if (line.size() + 1 + item.size() > 120 && line != head) {
      out << line << "\n";
      line = hang + item;
    } else {
      line += (line == head ? "" : " ") + item;
    }
  }
  out << line << "\n";
  return out.str();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: droplet_stub TEMPLATE OUTPUT\n";
    return 2;
  }
  const std::filesystem::path input = argv[1], output = argv[2];
  std::ifstream in(input);
  if (!in) {
    std::cerr << "droplet_stub: " << input.string() << ": cannot be read\n";
    return 1;
  }
  const std::string marker = "@DROPLET_PARAMS_FIELDS@";
  std::ostringstream text;
  int found = 0;
  for (std::string line; std::getline(in, line);) {
    const auto at = line.find(marker);
    if (at == std::string::npos) {
      text << line << "\n";
    } else {
      text << fields_block(line.substr(0, at));
      ++found;
    }
  }
  if (found != 1) {
    std::cerr << "droplet_stub: " << input.string() << ": needs the line " << marker << " once, not " << found
              << " times\n";
    return 1;
  }
  const std::filesystem::path partial = output.string() + ".tmp";
  {
    std::ofstream out(partial, std::ios::trunc);
    out << text.str();
    if (!out.flush()) {
      std::cerr << "droplet_stub: " << partial.string() << ": cannot be written\n";
      return 1;
    }
  }
  std::error_code error;
  std::filesystem::rename(partial, output, error);
  if (error) {
    std::cerr << "droplet_stub: " << output.string() << ": " << error.message() << "\n";
    std::filesystem::remove(partial, error);
    return 1;
  }
  return 0;
}
