// The Z3 field obligations through ctest, and evidence that they can fail: the same
// obligation builders instantiated with planted-bug kernels must produce FAILED verdicts
// with counterexamples, exactly for the fields the bug affects.
#include <gtest/gtest.h>

#include <string>

#include "core/xy/tmc2130/regmap.hpp"
#include "models/xy/smt/modules.hpp"
#include "models/xy/smt/tmc2130.hpp"

namespace {

namespace chip = ap::xy_tmc2130;
namespace st = ap::model::smt::xy_tmc2130;
using ap::model::smt::Verdict;

constexpr unsigned kTimeoutMs = 20000;

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

TEST(tmc2130_proof, every_field_obligation_is_proved) {
  ap::model::smt::ObligationList list;
  ap::model::smt::add_tmc2130_obligations(list);
  ASSERT_EQ(list.size(), 3 * chip::kFieldCount);
  for (const auto& o : list) {
    const auto r = ap::model::smt::run(o, kTimeoutMs);
    EXPECT_EQ(r.verdict, Verdict::Proved) << o.name << ": " << r.counterexample;
  }
}

TEST(tmc2130_proof, registry_contains_the_module) {
  std::size_t n = 0;
  for (const auto& o : ap::model::smt::xy_obligations()) n += o.name.rfind("tmc2130.", 0) == 0 ? 1u : 0u;
  EXPECT_EQ(n, 3 * chip::kFieldCount);
}

// TMC-API's FIELD_WRITE where FIELD_UPDATE was meant: the old word is dropped.
struct FieldWriteKernel : st::CodeKernel {
  template <class W>
  static W insert(W old, W mask, unsigned shift, W value) {
    return ((value << shift) & mask) | (old & (old ^ old));
  }
};

// The trailing "& mask" forgotten: harmless for unsigned in-range values, but a negative
// signed value sign-extends into the neighbouring bits.
struct NoFinalMaskKernel : st::CodeKernel {
  template <class W>
  static W insert(W old, W mask, unsigned shift, W value) {
    return (old & ~mask) | (value << shift);
  }
};

// Sign extension skipped: signed fields read back as their raw unsigned bits.
struct NoSignExtendKernel : st::CodeKernel {
  template <class W>
  static W sign_extend(W raw, W) {
    return raw;
  }
};

template <class K>
ap::model::smt::ObligationList planted() {
  ap::model::smt::ObligationList list;
  st::add_obligations_using<K>(list, "planted.");
  return list;
}

// A field that fills its whole register (MSLUTn) has no other bits to clobber, so there
// FIELD_WRITE is harmless and the proof must still say PROVED.
TEST(tmc2130_proof, field_write_bug_fails_isolation_for_every_partial_field) {
  const auto all = planted<FieldWriteKernel>();
  for (const auto& f : chip::kFields) {
    ap::model::smt::ObligationList one;
    for (const auto& o : all) {
      if (o.name == "planted." + st::field_path(f) + ".isolation") one.push_back(o);
    }
    ASSERT_EQ(one.size(), 1u);
    const auto r = ap::model::smt::run(one[0], kTimeoutMs);
    if (f.mask == 0xFFFFFFFFu) {
      EXPECT_EQ(r.verdict, Verdict::Proved) << one[0].name;
    } else {
      EXPECT_EQ(r.verdict, Verdict::Failed) << one[0].name;
      EXPECT_NE(r.counterexample.find("old="), std::string::npos) << one[0].name;
    }
  }
}

TEST(tmc2130_proof, missing_mask_fails_exactly_the_signed_fields) {
  for (const auto& o : planted<NoFinalMaskKernel>()) {
    if (!ends_with(o.name, ".isolation")) continue;
    const std::string path = o.name.substr(std::string("planted.").size());
    bool is_signed = false;
    for (const auto& f : chip::kFields) {
      if (path == st::field_path(f) + ".isolation") is_signed = f.is_signed;
    }
    const auto r = ap::model::smt::run(o, kTimeoutMs);
    EXPECT_EQ(r.verdict, is_signed ? Verdict::Failed : Verdict::Proved) << o.name << " " << r.counterexample;
  }
}

TEST(tmc2130_proof, missing_sign_extension_fails_signed_readback) {
  unsigned failed = 0;
  for (const auto& o : planted<NoSignExtendKernel>()) {
    if (!ends_with(o.name, ".readback")) continue;
    const auto r = ap::model::smt::run(o, kTimeoutMs);
    failed += r.verdict == Verdict::Failed ? 1u : 0u;
    if (o.name.find("COOLCONF.sgt") != std::string::npos) {
      EXPECT_EQ(r.verdict, Verdict::Failed) << r.counterexample;
    }
  }
  unsigned signed_fields = 0;
  for (const auto& f : chip::kFields) signed_fields += f.is_signed ? 1u : 0u;
  EXPECT_EQ(failed, signed_fields);
}

}  // namespace
