// The transition table of the axis (docs/motion.md §4 "The reconstructed graph (Obr. 7-16; G7,
// G8)"): Tab. 7-3's letters plus the edges it is missing, exactly one edge per (phase, class),
// each letter's guard and target phase, and the names traces print. One table and its
// readers: step() looks its edge up here, the tests check it total and deterministic, and the
// proofs mirror edge_for() and edge_guard() (models/xy/smt/axis_encoding.hpp).
#include "core/xy/axis/axis.hpp"

namespace ap::xy_axis {
namespace {

constexpr std::array<std::array<Edge, kClassCount>, kPhaseCount> kTable = {{
    //            EStop     EndMin   EndMax   Halt     Faster   Same     Slower
    /* Stop  */ {{Edge::I, Edge::I, Edge::I, Edge::I, Edge::A, Edge::I, Edge::I}},
    /* Accel */ {{Edge::X, Edge::G, Edge::H, Edge::E, Edge::J, Edge::B, Edge::D}},
    /* Const */ {{Edge::X, Edge::G, Edge::H, Edge::E, Edge::M, Edge::L, Edge::C}},
    /* Decel */ {{Edge::X, Edge::G, Edge::H, Edge::E, Edge::F, Edge::N, Edge::K}},
}};

}  // namespace

Edge edge_for(Phase p, Class c) {
  const auto pi = static_cast<uint8_t>(p);
  const auto ci = static_cast<uint8_t>(c);
  if (pi >= kPhaseCount || ci >= kClassCount) {
    return Edge::X;
  }
  return kTable[pi][ci];
}

bool edge_guard(Edge e, Phase p, Class c) {
  const bool stop = p == Phase::Stop;
  const bool moving = p == Phase::Accel || p == Phase::Const || p == Phase::Decel;
  switch (e) {
    case Edge::A: return stop && c == Class::Faster;
    case Edge::I: return stop && c != Class::Faster;
    case Edge::X: return moving && c == Class::EStop;
    case Edge::G: return moving && c == Class::EndMin;
    case Edge::H: return moving && c == Class::EndMax;
    case Edge::E: return moving && c == Class::Halt;
    case Edge::J: return p == Phase::Accel && c == Class::Faster;
    case Edge::B: return p == Phase::Accel && c == Class::Same;
    case Edge::D: return p == Phase::Accel && c == Class::Slower;
    case Edge::M: return p == Phase::Const && c == Class::Faster;
    case Edge::L: return p == Phase::Const && c == Class::Same;
    case Edge::C: return p == Phase::Const && c == Class::Slower;
    case Edge::F: return p == Phase::Decel && c == Class::Faster;
    case Edge::N: return p == Phase::Decel && c == Class::Same;
    case Edge::K: return p == Phase::Decel && c == Class::Slower;
  }
  return false;
}

Phase edge_target(Edge e, Phase from) {
  switch (e) {
    case Edge::A: case Edge::J: case Edge::M: case Edge::F: return Phase::Accel;
    case Edge::B: case Edge::L: case Edge::N: return Phase::Const;
    case Edge::C: case Edge::D: case Edge::K: return Phase::Decel;
    case Edge::E: case Edge::G: case Edge::H: case Edge::X: return Phase::Stop;
    case Edge::I: return from;
  }
  return Phase::Stop;
}

char edge_letter(Edge e) {
  constexpr std::array<char, kEdgeCount> k = {'A', 'B', 'C', 'D', 'E', 'F', 'G', 'H', 'I', 'J', 'K', 'L', 'M', 'N', 'X'};
  const auto i = static_cast<uint8_t>(e);
  return i < kEdgeCount ? k[i] : '?';
}

const char* phase_name(Phase p) {
  switch (p) {
    case Phase::Stop: return "STOP";
    case Phase::Accel: return "ACCEL";
    case Phase::Const: return "CONST";
    case Phase::Decel: return "DECEL";
  }
  return "?";
}

const char* mode_name(Mode m) {
  switch (m) {
    case Mode::Idle: return "idle";
    case Mode::Jog: return "jog";
    case Mode::Position: return "position";
    case Mode::Home: return "home";
  }
  return "?";
}

}  // namespace ap::xy_axis
