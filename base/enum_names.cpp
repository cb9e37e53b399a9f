// The choices' text of enum_names.h.

#include "base/enum_names.h"

namespace weft::base {

std::string choices_text(const std::vector<std::string>& names) {
  std::string text = "one of ";
  for (std::size_t k = 0; k < names.size(); ++k) text += (k ? ", '" : "'") + names[k] + "'";
  return text;
}

}  // namespace weft::base
