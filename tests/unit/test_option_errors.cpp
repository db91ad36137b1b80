// Errors about an option of a library call: the library's OptionError names the Options field,
// never a front-end's flag; the command line words it with the flag that sets the field, as
// before the library spoke its own fields (the messages below are those it printed then).
#include <gtest/gtest.h>

#include <string>

#include "cli_run.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/design_study.hpp"
#include "emnet/studies/switching_sweep.hpp"
#include "emnet/studies/transient_study.hpp"
#include "emnet/verification/crosscheck.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

using emnet::testing::kFishfin;

// The OptionError `run` throws; fails the test when it throws none.
template <class Run>
OptionError option_error_of(Run&& run) {
  try {
    run();
  } catch (const OptionError& error) {
    return error;
  }
  ADD_FAILURE() << "no OptionError";
  return OptionError("", "");
}

std::string dashed(const std::string& field) {
  return "--" + field;
}

// The command line's standard error for `arguments`: one line, exit status 2.
std::string cli_error(const std::string& arguments) {
  const testing::CliRun run = testing::run_emnet(arguments);
  EXPECT_EQ(run.status, 2) << arguments << ": " << run.err;
  return run.err;
}

TEST(OptionError, NamesTheFieldAndRendersOtherFieldsByTheFrontEndsNames) {
  const OptionError plain("samples", "must be from 8 to 1000000 (inclusive)");
  EXPECT_EQ(plain.field(), "samples");
  EXPECT_EQ(plain.where(), "samples");
  EXPECT_EQ(plain.key(), "samples");
  EXPECT_EQ(plain.reason(), "must be from 8 to 1000000 (inclusive)");
  EXPECT_STREQ(plain.what(), "samples: key 'samples': must be from 8 to 1000000 (inclusive)");
  EXPECT_EQ(plain.message_with(dashed),
            "--samples: key '--samples': must be from 8 to 1000000 (inclusive)");

  const OptionError between =
      OptionError::between("reduce", "method", "{reduce} replaces the exact method, not shooting");
  EXPECT_STREQ(between.what(),
               "reduce: key 'method': reduce replaces the exact method, not shooting");
  EXPECT_EQ(between.message_with(dashed),
            "--reduce: key '--method': --reduce replaces the exact method, not shooting");

  const OptionError with_key("probe", "position outside the beam", "deflection@2m");
  EXPECT_EQ(with_key.message_with(dashed),
            "--probe: key 'deflection@2m': position outside the beam");

  const OptionError in_file =
      OptionError::in_file("variants", "v.csv:3", "", "no variant {x} {Not} {}");
  EXPECT_EQ(in_file.message_with(dashed), "v.csv:3: key '--variants': no variant --x {Not} {}");
}

TEST(OptionError, LibraryOptionsNameTheirFields) {
  SwitchingSweepOptions sweep;
  sweep.samples = 4;
  EXPECT_EQ(option_error_of([&] { sweep.validate(); }).field(), "samples");

  DesignStudyOptions study;
  study.threads = 2000;
  EXPECT_EQ(option_error_of([&] { study.validate(); }).field(), "threads");
  const Variation random =
      parse_variation(read_scene(kFishfin), "beam.bending_stiffness=uniform(90%,110%)");
  EXPECT_EQ(option_error_of([&] { make_variants({random}, 0, 1); }).field(), "samples");

  TransientStudyOptions transient;
  transient.periods = -1.0;
  const OptionError periods = option_error_of([&] { transient.validate(); });
  EXPECT_EQ(periods.field(), "periods");
  EXPECT_STREQ(periods.what(), "periods: key 'periods': must be > 0 and at most 1e6 (inclusive)");

  CrosscheckOptions crosscheck;
  crosscheck.tran_periods = 0.0;
  EXPECT_EQ(option_error_of([&] { crosscheck.validate(); }).field(), "tran_periods");

  const Model model = prepare_model(read_scene(kFishfin));
  const OptionError probe = option_error_of([&] { model.parse_probe("deflection@2m"); });
  EXPECT_EQ(probe.field(), "probe");
  EXPECT_EQ(probe.key(), "deflection@2m");
}

// An override's error is the library's: where "override", which the command line calls --set.
TEST(OptionError, AnOverrideIsNamedOverrideByTheLibrary) {
  try {
    read_scene(kFishfin, {"beam.lenght=0.2"});
    FAIL() << "accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(error.where(), "override");
    EXPECT_EQ(error.key(), "beam.lenght");
  }
}

TEST(OptionErrorCli, TheCommandLineNamesTheFlags) {
  EXPECT_EQ(cli_error("sweep-switching " + kFishfin + " --samples 4"),
            "emnet: error: --samples: key '--samples': must be from 8 to 1000000 (inclusive)\n");
  EXPECT_EQ(cli_error("sweep-switching " + kFishfin + " --reduce --method shooting"),
            "emnet: error: --reduce: key '--method': --reduce replaces the exact method, not "
            "shooting\n");
  EXPECT_EQ(cli_error("sweep-switching " + kFishfin + " --step 0"),
            "emnet: error: --from/--to/--step: key '--step': need 0 < from <= to and step > 0 "
            "(frequencies in Hz)\n");
  EXPECT_EQ(cli_error("study " + kFishfin + " --vary 'beam.bending_stiffness=uniform(90%,110%)'"),
            "emnet: error: --samples: key '--samples': a random variation (uniform, normal, "
            "lognormal) needs --samples N\n");
  EXPECT_EQ(cli_error("study " + kFishfin + " --vary beam.bending_stiffness=1,2 --threads 2000"),
            "emnet: error: --threads: key '--threads': must be from 1 to 1024 (0: every core)\n");
  EXPECT_EQ(cli_error("tran " + kFishfin + " --periods -1"),
            "emnet: error: --periods: key '--periods': must be > 0 and at most 1e6 (inclusive)\n");
  EXPECT_EQ(cli_error("crosscheck " + kFishfin + " --analysis tran --periods 0"),
            "emnet: error: --periods: key '--periods': must be > 0 and at most 1000\n");
  EXPECT_EQ(cli_error("static " + kFishfin + " --set beam.lenght=0.2"),
            "emnet: error: --set: key 'beam.lenght': unknown key (did you mean "
            "'beam.length'?)\n");
  EXPECT_EQ(cli_error("static " + kFishfin + " --probe deflection@2m")
                .rfind("emnet: error: --probe: key 'deflection@2m': position outside the beam", 0),
            0u);
  EXPECT_EQ(cli_error("identify " + kFishfin + " --resonance 6 --fit beam.left"),
            "emnet: error: --fit: key 'beam.left': is not a number but a choice key; identify "
            "fits a numeric key\n");
}

}  // namespace
}  // namespace emnet
