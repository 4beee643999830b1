// The scenario's actions carried out by the simulated PC (pc_actions.hpp, docs/sim.md "The
// simulated PC", docs/scenarios.md): apart from the transport and the checks, so that a verb is
// added or changed here alone.
#include "pc_actions.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/xy/storage/parameters.hpp"
#include "pc/xy/gcode/program.hpp"
#include "protocol/xy/codec/commands.hpp"
#include "protocol/xy/codec/subscribers.hpp"
#include "sim/xy/params.hpp"
#include "pc_transport.hpp"

namespace ap::sim::xy {

namespace sc = ap::sim::xy::scenario;
using xy_codec::CommandId;

namespace {

// The program of a `gcode` action: the path as written, else from the source tree.
xy_pcgcode::Program load_gcode(PcContext& pc, const sc::Action& a, const std::string& where) {
  std::string path = a.word;
  if (!std::filesystem::is_regular_file(path)) path = std::string(AP_SOURCE_DIR) + "/" + a.word;
  std::ifstream in(path);
  if (!in) {
    pc.fail(where + ": cannot read G-code file " + a.word);
    return {};
  }
  std::ostringstream text;
  text << in.rdbuf();
  xy_pcgcode::Options o;
  o.dialect = a.word2 == "thesis" ? xy_gcode::Dialect::Thesis : xy_gcode::Dialect::Tolerant;
  try {
    xy_pcgcode::Program p = xy_pcgcode::translate(text.str(), o, a.word);
    // The board queues 16 segments (docs/cnc.md "Refusals"); the simulated PC sends a program
    // at once, so a longer one would meet QueueFull.
    if (p.segment_frames > 16) {
      pc.fail(where + ": " + a.word + " has more than 16 XY segments (the board's queue)");
      return {};
    }
    return p;
  } catch (const xy_pcgcode::ProgramError& e) {
    pc.fail(where + ": " + e.what());
  }
  return {};
}

std::int32_t um(const sc::Action& a) { return static_cast<std::int32_t>(std::llround(a.amount ? a.amount->value : 0.0)); }

void release_and_submit(BoardPc& b, HeldKey& x, xy_client::Part part, CommandId id, std::int32_t data, std::int64_t t) {
  x.jog = 0;
  x.jogging = false;
  submit(b, part, id, data, t);
}

}  // namespace

PcMech assumed_mechanics(const sc::Scenario& s) {
  PcMech mech;
  const xy_storage::ParameterSet d = xy_storage::defaults();
  double lead = d.lead_pitch_um, steps = d.steps_per_rev, micro = d.microsteps;
  mech.fast_um_s = d.fast_speed_um_s;
  mech.slow_um_s = d.slow_speed_um_s;
  mech.start_um_s = d.start_speed_um_s;
  mech.accel_um_s2 = d.max_acceleration_um_s2;
  mech.home_um_s = d.homing_speed_um_s;
  for (const sc::Setup& st : s.setup) {
    if ((st.key == "param" || st.key == "fram") && st.amount) {
      const auto id = param_by_name(st.word);
      if (id == xy_storage::ParamId::LeadPitch) lead = st.amount->value;
      if (id == xy_storage::ParamId::StepsPerRev) steps = st.amount->value;
      if (id == xy_storage::ParamId::Microsteps) micro = st.amount->value;
      if (id == xy_storage::ParamId::FastSpeed) mech.fast_um_s = st.amount->value;
      if (id == xy_storage::ParamId::MaxAcceleration) mech.accel_um_s2 = st.amount->value;
    }
  }
  mech.um_per_ustep = lead / (steps * micro);
  mech.max_speed_um_s = std::max({mech.fast_um_s, mech.slow_um_s, mech.home_um_s});
  mech.min_accel_um_s2 = mech.accel_um_s2;
  return mech;
}

void set_up(PcContext& pc, Boards& boards) {
  for (auto& b : boards) {
    for (const sc::Setup& st : pc.s.setup) {
      const auto v = [&] { return std::to_string(std::llround(st.amount ? st.amount->value : 0.0)); };
      if (st.key == "battery") env(pc, *b, "battery " + v(), 0);
      else if (st.key == "charger" || st.key == "usb") env(pc, *b, st.key + (st.word == "plugged" ? " 1" : " 0"), 0);
      else if (st.key == "ble") env(pc, *b, "ble " + st.word, 0);
      else if (st.key == "encoder") env(pc, *b, "encoder " + st.word, 0);
      else if (st.key == "temperature") env(pc, *b, "temperature " + v(), 0);
      else if (st.key == "pos") env(pc, *b, std::string("pos ") + st.axis + " " + v(), 0);
      else if (st.key == "endstop") env(pc, *b, std::string("endstop_at ") + st.axis + " " + st.word + " " + v(), 0);
      else env(pc, *b, st.key + " " + st.word + " " + v(), 0);   // param / fram
    }
    env(pc, *b, "boot", 0);
  }
}

void apply(PcContext& pc, Boards& boards, const sc::Action& a, std::int64_t t) {
  PcMech& mech = pc.mech;
  for (auto& bp : boards) {
    BoardPc& b = *bp;
    if (!a.target.all && a.target.board != b.id) continue;
    const std::size_t ai = a.axis == 'y' ? 1 : 0;
    const xy_client::Part part = ai == 1 ? xy_client::Part::Y : xy_client::Part::X;
    HeldKey& x = b.keys[ai];
    const std::string where = pc.s.name + ".scn:" + std::to_string(a.line);
    switch (a.verb) {
      case sc::Verb::jog:
        // The jog is a command like any other; the held level then rides in every new frame.
        x.jog = (a.word == "-" ? -1 : 1) * (a.word2 == "fast" ? xy_codec::kJogFast : xy_codec::kJogSlow);
        x.jogging = true;
        submit(b, part, CommandId::Jog, x.jog, t);
        break;
      // Any other command of the axis releases the held key.
      case sc::Verb::stop: release_and_submit(b, x, part, CommandId::Stop, 0, t); break;
      case sc::Verb::go_to:
        release_and_submit(b, x, part, a.word2 == "slow" ? CommandId::GotoSlow : CommandId::Goto, um(a), t);
        break;
      case sc::Verb::move:
        release_and_submit(b, x, part, a.word2 == "slow" ? CommandId::MoveSlow : CommandId::Move, um(a), t);
        break;
      case sc::Verb::home: release_and_submit(b, x, part, CommandId::Home, 0, t); break;
      case sc::Verb::set_speed:
        submit(b, xy_client::Part::Unit, a.word == "fast" ? CommandId::SetFastSpeed : CommandId::SetSlowSpeed, um(a), t);
        if (a.word == "fast") mech.fast_um_s = um(a);
        mech.max_speed_um_s = std::max(mech.max_speed_um_s, static_cast<double>(um(a)));
        break;
      case sc::Verb::set_accel:
        submit(b, xy_client::Part::Unit, CommandId::SetAccel, um(a), t);
        mech.accel_um_s2 = um(a);
        mech.min_accel_um_s2 = std::min(mech.min_accel_um_s2, static_cast<double>(um(a)));
        break;
      case sc::Verb::save: submit(b, xy_client::Part::Unit, CommandId::SaveParams, 0, t); break;
      case sc::Verb::peripherals:
        submit(b, xy_client::Part::Unit, a.word == "on" ? CommandId::PeriphOn : CommandId::PeriphOff, 0, t);
        break;
      case sc::Verb::tmc:
        if (a.word == "IRUN" || a.word == "IHOLD") {
          submit(b, part, a.word == "IRUN" ? CommandId::SetIrun : CommandId::SetIhold, um(a), t);
        } else {
          pc.fail(where + ": tmc " + a.word + " cannot be set over the protocol (only IRUN and IHOLD have commands)");
        }
        break;
      case sc::Verb::subscribe:
      case sc::Verb::unsubscribe: {
        std::vector<xy_codec::SubscriberId> ids;
        if (a.word == "battery" || a.word == "all") ids.push_back(xy_codec::SubscriberId::BatteryMv);
        if (a.word == "charge_current" || a.word == "all") ids.push_back(xy_codec::SubscriberId::ChargeMa);
        if (a.word == "temperature" || a.word == "all") ids.push_back(xy_codec::SubscriberId::TemperatureMc);
        if (a.word == "rotation" || a.word == "all") ids.push_back(xy_codec::SubscriberId::RotationMdeg);
        for (const auto id : ids) {
          const auto it = std::find(pc.subscribed.begin(), pc.subscribed.end(), id);
          if (a.verb == sc::Verb::subscribe && it == pc.subscribed.end()) pc.subscribed.push_back(id);
          if (a.verb == sc::Verb::unsubscribe && it != pc.subscribed.end()) pc.subscribed.erase(it);
        }
        break;
      }
      case sc::Verb::gcode: {
        // docs/cnc.md: the PC parses the program and sends it as path frames; the two parts of
        // each frame go to the client back to back, so they leave in one frame.
        const xy_pcgcode::Program prog = load_gcode(pc, a, where);
        for (const xy_pcgcode::Frame& f : prog.frames) {
          if (f.y_id == CommandId::Nop) {
            submit(b, xy_client::Part::Unit, f.x_id, f.x, t);
          } else {
            submit(b, xy_client::Part::X, f.x_id, f.x, t);
            submit(b, xy_client::Part::Y, f.y_id, f.y, t);
          }
        }
        break;
      }
      case sc::Verb::raw: {
        const Bytes bytes(a.word.begin(), a.word.end());
        b.down->push(t, bytes, b.verdict.to_board);
        break;
      }
      case sc::Verb::link_cut: {
        const std::int64_t until = a.amount ? t + static_cast<std::int64_t>(a.amount->value) : pc.s.duration_us + 1;
        b.down->cut_until(until);
        b.up->cut_until(until);
        break;
      }
      case sc::Verb::link_restore:
        b.down->cut_until(-1);
        b.up->cut_until(-1);
        break;
      case sc::Verb::charger: env(pc, b, std::string("charger ") + (a.word == "plug" ? "1" : "0"), t); break;
      case sc::Verb::usb: env(pc, b, std::string("usb ") + (a.word == "plug" ? "1" : "0"), t); break;
      case sc::Verb::battery: env(pc, b, "battery " + std::to_string(um(a)), t); break;
      case sc::Verb::temperature: env(pc, b, "temperature " + std::to_string(um(a)), t); break;
      case sc::Verb::rotate: env(pc, b, "rotate " + std::to_string(um(a)), t); break;
      case sc::Verb::ble: env(pc, b, "ble " + a.word, t); break;
      case sc::Verb::endstop: env(pc, b, std::string("endstop ") + a.axis + " " + a.word + " " + a.word2, t); break;
      case sc::Verb::button: env(pc, b, "button " + a.word, t); break;
      case sc::Verb::reboot:
        env(pc, b, "reboot", t);
        break;
    }
  }
}

}  // namespace ap::sim::xy
