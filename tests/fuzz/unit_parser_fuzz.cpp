// libFuzzer target: any bytes as a quantity with units ("0.019 gf/cm^2"),
// read as each kind of quantity. parse_quantity must return a finite value of that kind or
// throw UnitError; anything else is a finding. Built with -DWEFT_FUZZ=ON (docs/reliability.md).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "app/scene/units.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  using weft::app::Quantity;
  for (Quantity kind : {Quantity::length, Quantity::time, Quantity::areal_density,
                        Quantity::force_per_length, Quantity::bending_rigidity, Quantity::speed,
                        Quantity::acceleration, Quantity::inverse_time, Quantity::angle,
                        Quantity::stress}) {
    try {
      if (!std::isfinite(weft::app::parse_quantity(text, kind))) std::abort();
    } catch (const weft::app::UnitError&) {
      // bad input, reported as such
    }
  }
  return 0;
}
