#pragma once
#include <cstddef>
#include <string_view>
#include <vector>

namespace stengmc {

//! What happened to an asperity at an instant.
enum class EventKind {
  stick,        //!< Model 1: velocity reached zero and static friction holds
  slip,         //!< Model 1: static friction exceeded, sliding starts
  reversal,     //!< Model 1: velocity reached zero, sliding continues the other way
  overtake,     //!< Model 2: relative velocity v_b - x' turned negative (asperity overtakes the belt)
  regrip,       //!< Model 2: relative velocity turned positive again
  domain_exit,  //!< x reached l: the S-TENG element formulas no longer hold (MODEL.md §2)
};

//! Name written to files and screens.
constexpr std::string_view event_name(EventKind kind) {
  switch (kind) {
    case EventKind::stick: return "stick";
    case EventKind::slip: return "slip";
    case EventKind::reversal: return "reversal";
    case EventKind::overtake: return "overtake";
    case EventKind::regrip: return "regrip";
    case EventKind::domain_exit: return "domain_exit";
  }
  return "unknown";
}

//! One event of one asperity.
struct Event {
  double time_s = 0.0;     //!< when [s]
  std::size_t asperity = 0;  //!< index of the asperity
  EventKind kind = EventKind::stick;
};

}  // namespace stengmc
