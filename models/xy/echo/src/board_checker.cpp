#include "models/xy/echo/board_checker.hpp"

#include "core/xy/frame/echo_codec.hpp"
#include "core/xy/storage/store.hpp"

namespace ap::model::xy_echo {

namespace {
constexpr std::size_t kEventsPerTick = 4;  // docs/board.md: at most 4 frame events per tick
constexpr std::size_t kRing = 256;         // docs/board.md: the 256-byte receive ring
}  // namespace

void LinkTwin::rx(std::span<const std::uint8_t> bytes) {
  for (const std::uint8_t b : bytes) {
    if (ring_.size() < kRing) ring_.push_back(b);  // overflow: dropped (counted by the board)
  }
}

std::optional<FrameEvent> LinkTwin::next() {
  std::size_t used = 0;
  std::optional<FrameEvent> out;
  while (used < ring_.size() && !out) {
    if (auto e = framer_.push(ring_[used++])) out = FrameEvent{e->rejection, e->frame};
  }
  ring_.erase(ring_.begin(), ring_.begin() + static_cast<std::ptrdiff_t>(used));
  return out;
}

Boot boot_facts(const xy_board::Board& board, const xy_board::Inputs& in, std::array<bool, kAxes> saved) {
  Boot b;
  for (std::size_t a = 0; a < kAxes; ++a) {
    b.homed[a] = in.encoder[a].valid != 0 || saved[a];
    b.pos[a] = board.axis_state(static_cast<xy_board::Axis>(a)).pos;
    b.endstop_min[a] = in.endstop_min[a] != 0;
    b.endstop_max[a] = in.endstop_max[a] != 0;
  }
  return b;
}

xy_storage::ParameterSet stored_set(model::Mb85rs256b chip) {
  xy_storage::ParameterStore store(chip.bus());
  (void)store.boot();
  return store.current();
}

Boot boot_facts(const xy_board::Board& board, const xy_board::Inputs& in, const xy_storage::ParameterSet& stored) {
  Boot b = boot_facts(board, in, std::array<bool, kAxes>{stored.step_counts_valid, stored.step_counts_valid});
  b.params = stored;
  return b;
}

Env env_of(const xy_board::Inputs& in) {
  Env e;
  e.usb = in.usb;
  e.charger = in.charger;
  e.battery_mv = in.battery_mv;
  e.charge_ma = in.charge_ma;
  e.ble_status1 = in.ble_status1;
  e.ble_status2 = in.ble_status2;
  e.button = in.button;
  for (std::size_t a = 0; a < kAxes; ++a) {
    e.endstop_min[a] = in.endstop_min[a] != 0;
    e.endstop_max[a] = in.endstop_max[a] != 0;
  }
  return e;
}

Sensors sensors_of(const model::xy_tmp117::Device& t, ap::xy_i2c::Status t_answers, const model::xy_icm20789::Device& g,
                   ap::xy_i2c::Status g_answers) {
  Sensors s;
  s.tmp117.answers = t_answers;
  // docs/sensors.md: only DID[11:0] identifies the part; the revision nibble may differ.
  s.tmp117.identity_ok = (t.reg(ap::xy_tmp117::Reg::DeviceId) & 0x0FFFU) == 0x0117U;
  s.temp_result = t.reg(ap::xy_tmp117::Reg::TempResult);
  s.gyro.answers = g_answers;
  namespace reg = ap::xy_icm20789::reg;
  s.gyro.identity_ok = g.reg(reg::kWhoAmI) == 0x03;  // DS-000169
  // GYRO_ZOUT_H/_L: what a read gives, the ±250 °/s code while awake.
  const auto code = static_cast<std::uint16_t>((unsigned{g.reg(reg::kGyroZoutH)} << 8) | g.reg(reg::kGyroZoutL));
  s.gyro_z = static_cast<std::int16_t>(code);
  return s;
}

Motion motion_of(const xy_board::Board& b) {
  Motion m;
  for (std::size_t a = 0; a < kAxes; ++a) {
    const auto ax = static_cast<xy_board::Axis>(a);
    const xy_axis::State& s = b.axis_state(ax);
    m[a].phase = static_cast<Phase>(s.phase);
    m[a].pos = s.pos;
    m[a].steps = b.motor_output(ax).steps;
    m[a].dir = b.motor_output(ax).dir;
  }
  // The path's progress (docs/echo-model.md "The coordinated path"): physics, not a verdict.
  m.path.active = b.path().active();
  m.path.queued = static_cast<std::uint32_t>(b.path().queued());
  const xy_path::Status st = b.path().status();
  m.path.chain_running = st == xy_path::Status::Running || st == xy_path::Status::Stopping;
  return m;
}

std::vector<std::string> BoardChecker::after_tick(std::span<const EchoBytes> sent, const Sensors& sensors) {
  std::vector<std::string> bad;
  Env env = env_of(board_.inputs());
  env.sensors = sensors;
  model_.begin_tick(env);
  // docs/board.md "One cycle" step 3: frame events until four are answered, the ring is
  // empty, or a new frame was taken (docs/protocol.md "Two frames in one cycle": the bytes
  // behind it wait for the next tick).
  while (model_.answers_this_tick() < kEventsPerTick && !model_.took_frame_this_tick()) {
    const auto ev = link_.next();
    if (!ev) break;
    model_.frame(*ev);
  }
  const auto want = model_.end_tick(motion_of(board_));
  const std::string at = "tick " + std::to_string(board_.ticks()) + ": ";
  for (auto& v : model_.take_violations()) bad.push_back(at + "motion: " + v);
  if (sent.size() != want.size()) {
    bad.push_back(at + std::to_string(sent.size()) + " echoes sent, the model expects " + std::to_string(want.size()));
  }
  for (std::size_t i = 0; i < sent.size() && i < want.size(); ++i) {
    xy_frame::EchoFrame e;
    const xy_frame::Rejection r = xy_frame::parse_echo(sent[i], e);
    if (!r.ok()) {
      bad.push_back(at + "echo " + std::to_string(i) + " does not parse (error " +
                    std::to_string(static_cast<int>(r.error)) + " at " + std::to_string(r.offset) + ")");
      continue;
    }
    if (auto m = check(want[i], e)) bad.push_back(at + m->text);
  }
  return bad;
}

}  // namespace ap::model::xy_echo
