// Every class of bad input gives an InputError whose message names file:line:column, the key
// path, what was expected and what was found (and a hint where one helps).
//
// Each case appends a snippet to a small valid model (kBase, 13 lines), so the snippet's first
// line is line 14 of "model.toml"; columns are 1-based and point at the value (or the key for
// unknown keys, or the table header for missing keys).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/model/parse.hpp"

namespace geardyn::model {
namespace {

const std::string kBase = R"(version = 1
[[materials]]
name = "steel"
youngs_modulus = 2.1e11
poisson_ratio = 0.3
density = 7850
[[shafts]]
name = "rotor"
material = "steel"
[[shafts.elements]]
length = 0.5
outer_diameter = 0.05
divisions = 4
)";
constexpr int kBaseLines = 13;

struct ErrorCase {
  const char* name;
  std::string text;  ///< appended to kBase unless `whole` is set
  int line;          ///< line in the snippet (1 = its first line), or absolute when whole
  int column;
  std::string key;
  std::string expected;   ///< part of InputError::expected()
  std::string found;      ///< part of InputError::found()
  std::string hint = {};  ///< part of InputError::hint()
  bool whole = false;
};

std::optional<InputError> error_of(const std::string& text) {
  try {
    (void)analyses::parse_model(text, "model.toml");
  } catch (const InputError& e) {
    return e;
  }
  return std::nullopt;
}

class ModelErrors : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(ModelErrors, MessageNamesWhereWhatAndWhy) {
  const ErrorCase& c = GetParam();
  const std::string text = c.whole ? c.text : kBase + c.text;
  const auto e = error_of(text);
  ASSERT_TRUE(e.has_value()) << "no error for:\n" << text;
  const int line = c.whole ? c.line : kBaseLines + c.line;
  const std::string message = e->what();
  SCOPED_TRACE(message);
  EXPECT_EQ(e->where().file, "model.toml");
  EXPECT_EQ(e->where().line, line);
  EXPECT_EQ(e->where().column, c.column);
  EXPECT_NE(message.find(fmt::format("model.toml:{}:{}", line, c.column)), std::string::npos);
  EXPECT_EQ(e->key_path(), c.key);
  EXPECT_NE(message.find(c.key), std::string::npos);
  EXPECT_NE(e->expected().find(c.expected), std::string::npos) << "expected: " << e->expected();
  EXPECT_NE(message.find(c.expected), std::string::npos);
  EXPECT_NE(e->found().find(c.found), std::string::npos) << "found: " << e->found();
  EXPECT_NE(message.find(c.found), std::string::npos);
  EXPECT_NE(e->hint().find(c.hint), std::string::npos) << "hint: " << e->hint();
}

const ErrorCase kCases[] = {
    // --- syntax, structure, keys, types ---
    {"TomlSyntax", "[[bearings]\nnode = 1\n", 1, 12, "(syntax)", "valid TOML", "expected"},
    {"NonAsciiOutsideStrings", "[[bearings]]\nnode = \"rotor.0\"\nkxx = [1e6, \xc7\xa2]\n", 3, 13,
     "(syntax)", "non-ASCII characters only inside strings and comments", "the character U+01E2"},
    {"InvalidUtf8", "[[sensors]]\nname = \"\xff\"\n", 2, 9, "(syntax)", "valid UTF-8 text",
     "the byte 0xFF"},
    {"NonAsciiAfterLineContinuation", "version = 1\ntitle = \"\"\"first \\\n\xc2\xa7 2\"\"\"\n", 3,
     1, "(syntax)", "an ASCII character first on a line continued with a backslash",
     "the character U+00A7", "", true},
    // toml++ 3.3 has undefined behaviour classifying some non-ASCII characters after a
    // backslash (found by fuzz/model_fuzz); TOML escapes are ASCII, so they are refused first.
    {"NonAsciiEscapeInMultiLineString", "version = 1\ntitle = \"\"\"a \\\xef\xbb\xbd\"\"\"\n", 2,
     15, "(syntax)", "an escape sequence after the backslash", "the character U+FEFD", "", true},
    {"NonAsciiAfterBackslashSpace", "version = 1\ntitle = \"\"\"a \\  \xc2\xa7\"\"\"\n", 2, 17,
     "(syntax)", "an escape sequence after the backslash", "the character U+00A7", "", true},
    {"NonAsciiEscapeInString", "version = 1\ntitle = \"a \\\xc2\xa7\"\n", 2, 13, "(syntax)",
     "an escape sequence after the backslash", "the character U+00A7", "", true},
    {"QuoteAfterBareValue", "version = 1\ntitle = 0x\"a\"\n", 2, 11, "(syntax)",
     "a string only after", "a quote after 'x'", "", true},
    {"UnknownKeyDidYouMean", "lenght = 0.1\n", 1, 1, "shafts[0].elements[0].lenght",
     "a key of [[shafts.elements]]", "the unknown key 'lenght'", "did you mean 'length'?"},
    {"UnknownKeyWithoutUnitSuffix",
     "[[unbalances]]\nnode = \"rotor.1\"\nmass_eccentricity = 1e-4\nphase = 30\n", 4, 1,
     "unbalances[0].phase", "a key of [[unbalances]]", "the unknown key 'phase'",
     "did you mean 'phase_deg'?"},
    {"UnknownSection", "[[bearing]]\nnode = \"rotor.0\"\n", 1, 3, "bearing", "a key of top level",
     "the unknown key 'bearing'", "did you mean 'bearings'?"},
    {"KeyOfAnotherAnalysisType", "[[analyses]]\nname = \"m\"\ntype = \"modal\"\nspeed_count = 5\n",
     4, 1, "analyses[0].speed_count", "a key of [[analyses]] with type = \"modal\"",
     "the unknown key 'speed_count'",
     "type = \"campbell\", \"unbalance\", \"cyclic_modal\", \"mesh_force\", "
     "\"cyclic_forced_response\", \"gear_forced_response\", \"gear_whine\" and "
     "\"damper_ring_response\" only"},
    {"KeyOfAnotherGearType",
     "[[gear_meshes]]\ngear1 = \"rotor.0\"\ngear2 = \"rotor.1\"\nbase_radius1 = 0.1\n"
     "base_radius2 = 0.1\nstiffness = 1e8\nhelix_angle_deg = 20\n",
     7, 1, "gear_meshes[0].helix_angle_deg", "with type = \"spur\"",
     "the unknown key 'helix_angle_deg'", "\"helical\", \"spiral_bevel\" and \"hypoid\" only"},
    {"WrongTypeString", "[[bearings]]\nnode = \"rotor.0\"\nkxx = \"stiff\"\n", 3, 7,
     "bearings[0].kxx", "a number >= 0 or an array of them", "the string \"stiff\""},
    {"WrongTypeArrayForNumber", "[[point_masses]]\nnode = \"rotor.0\"\nmass = [1, 2]\n", 3, 8,
     "point_masses[0].mass", "a number > 0 [kg]", "an array of 2 entries"},
    {"WrongTypeSectionNotTable", "version = 1\ndamping = 3\n", 2, 11, "damping",
     "a table ([damping])", "the integer 3", "", true},
    {"WrongTypeTableNotArray", "[sensors]\nname = \"s\"\n", 1, 1, "sensors",
     "an array of tables ([[sensors]] headers)", "a table"},
    {"IntegerWrittenAsFloat", "[[analyses]]\nname = \"m\"\ntype = \"modal\"\nn_modes = 10.0\n", 4,
     11, "analyses[0].n_modes", "an integer in [1, 10000]", "the number 10",
     "write it without a decimal point"},
    {"EnumTypo", "[[shafts]]\nname = \"s2\"\nmaterial = \"steel\"\ntheory = \"timoshenco\"\n", 4,
     10, "shafts[1].theory", "one of \"timoshenko\" or \"euler_bernoulli\"",
     "the string \"timoshenco\"", "did you mean 'timoshenko'?"},
    {"BadDofName", "[[constraints]]\nnode = \"rotor.0\"\ndofs = [\"ux\", \"tz\"]\n", 3, 15,
     "constraints[0].dofs[1]", "DOF names", "the string \"tz\"", "did you mean"},
    {"NameWithDot", "[[nodes]]\nname = \"hub.1\"\nposition = [0, 0, 0]\n", 2, 8, "nodes[0].name",
     "a name (a string of letters", "the string \"hub.1\"", "'.' is not allowed"},
    {"ZeroAxis", "[[nodes]]\nname = \"hub\"\nposition = [0, 0, 0]\naxis = [0, 0, 0]\n", 4, 8,
     "nodes[0].axis", "not all zero", "[0, 0, 0]"},

    // --- required keys and alternatives ---
    {"MissingRequiredKey", "[[sensors]]\nname = \"s\"\nnode = \"rotor.0\"\n", 1, 1,
     "sensors[0].dof", "the key 'dof'", "a [[sensors]] table without it"},
    {"MissingKeyOfAlternative", "[[disks]]\nnode = \"rotor.1\"\nmass = 2.0\npolar_inertia = 0.1\n",
     1, 1, "disks[0].diametral_inertia", "the key 'diametral_inertia'",
     "'mass' without 'diametral_inertia'"},
    {"NoAlternativeGiven", "[[disks]]\nnode = \"rotor.1\"\n", 1, 1, "disks[0]",
     "one of (mass, polar_inertia, diametral_inertia) or (outer_diameter", "none of them"},
    {"BothAlternatives",
     "[[materials]]\nname = \"alu\"\nyoungs_modulus = 7e10\nshear_modulus = 2.6e10\n"
     "poisson_ratio = 0.33\ndensity = 2700\n",
     5, 17, "materials[1].poisson_ratio", "only one of shear_modulus or poisson_ratio",
     "both 'shear_modulus' and 'poisson_ratio'"},
    {"MissingVersion", "[[nodes]]\nname = \"a\"\nposition = [0, 0, 0]\n", 1, 1, "version",
     "the key 'version'", "without it", "", true},
    {"WrongVersion", "version = 2\n", 1, 11, "version", "an integer = 1", "2", "", true},
    {"ShaftWithoutElements", "[[shafts]]\nname = \"bare\"\nmaterial = \"steel\"\n", 1, 1,
     "shafts[1].elements", "at least 1 [[shafts.elements]] table", "none"},

    // --- non-physical values ---
    {"NegativeMass", "[[point_masses]]\nnode = \"rotor.0\"\nmass = -2\n", 3, 8,
     "point_masses[0].mass", "a finite number > 0 [kg]", "-2"},
    {"ZeroDiskMass",
     "[[disks]]\nnode = \"rotor.1\"\nmass = 0\npolar_inertia = 0.1\ndiametral_inertia = 0.05\n", 3,
     8, "disks[0].mass", "> 0", "0"},
    {"NegativeDirectStiffness", "[[bearings]]\nnode = \"rotor.0\"\nkxx = -1e6\n", 3, 7,
     "bearings[0].kxx", ">= 0", "-1000000"},
    {"InnerNotBelowOuter",
     "[[shafts]]\nname = \"tube\"\nmaterial = \"steel\"\n[[shafts.elements]]\nlength = 1\n"
     "outer_diameter = 0.05\ninner_diameter = 0.05\n",
     7, 18, "shafts[1].elements[0].inner_diameter", "a number < outer_diameter = 0.05 m", "0.05"},
    {"ZeroLength", "[[shafts.elements]]\nlength = 0\nouter_diameter = 0.05\n", 2, 10,
     "shafts[0].elements[1].length", "> 0", "0"},
    {"NegativeModulus",
     "[[materials]]\nname = \"soft\"\nyoungs_modulus = -7e10\nshear_modulus = 2.6e10\n"
     "density = 2700\n",
     3, 18, "materials[1].youngs_modulus", "a finite number > 0 [Pa]", "-70000000000"},
    {"NanValue", "[[point_masses]]\nnode = \"rotor.0\"\nmass = nan\n", 3, 8, "point_masses[0].mass",
     "finite", "nan"},
    {"DiskBoreTooLarge",
     "[[disks]]\nnode = \"rotor.1\"\nouter_diameter = 0.2\ninner_diameter = 0.3\n"
     "thickness = 0.02\nmaterial = \"steel\"\n",
     4, 18, "disks[0].inner_diameter", "< outer_diameter", "0.3"},
    {"AsymmetricCouplingMass",
     "[[couplings]]\nnode1 = \"rotor.0\"\nmass = [[1, 2, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0], "
     "[0, 0, 1, 0, 0, 0], [0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 1, 0], [0, 0, 0, 0, 0, 1]]\n",
     3, 8, "couplings[0].mass", "a symmetric mass matrix", "mass[0][1] = 2 but mass[1][0] = 0"},
    {"CouplingSizeForTwoNodes",
     "[[nodes]]\nname = \"hub\"\nposition = [0, 1, 0]\n[[couplings]]\nnode1 = \"rotor.0\"\n"
     "node2 = \"hub\"\nstiffness = [[1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0], "
     "[0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 1, 0], [0, 0, 0, 0, 0, 1]]\n",
     7, 13, "couplings[0].stiffness", "a 12x12 matrix", "a 6x6 matrix"},
    {"TimeStepNotBelowDuration",
     "[[analyses]]\nname = \"t\"\ntype = \"transient\"\nduration = 0.1\ntime_step = 0.5\n", 5, 13,
     "analyses[0].time_step", "a time step < duration = 0.1 s", "0.5 s"},

    // --- ranges that would be empty ---
    {"EmptySpeedRange",
     "[[analyses]]\nname = \"c\"\ntype = \"campbell\"\nspeed_start_rpm = 3000\n"
     "speed_stop_rpm = 1000\n",
     5, 18, "analyses[0].speed_stop_rpm", "a speed > speed_start_rpm = 3000 rpm", "1000 rpm"},
    {"EmptySpeedList", "[[analyses]]\nname = \"c\"\ntype = \"campbell\"\nspeed_rpm = []\n", 4, 13,
     "analyses[0].speed_rpm", "at least 1 value", "an empty array"},
    {"SpeedsNotIncreasing",
     "[[analyses]]\nname = \"c\"\ntype = \"campbell\"\nspeed_rpm = [0, 2000, 1000]\n", 4, 23,
     "analyses[0].speed_rpm[2]", "a value > the previous one, 2000", "1000"},
    {"EmptyFrequencyRange",
     "[[analyses]]\nname = \"h\"\ntype = \"harmonic\"\nfrequency_start_hz = 500\n"
     "frequency_stop_hz = 100\ninput_node = \"rotor.1\"\n",
     5, 21, "analyses[0].frequency_stop_hz", "a frequency > frequency_start_hz = 500 Hz", "100 Hz"},
    {"NoSpeedRangeGiven", "[[analyses]]\nname = \"u\"\ntype = \"unbalance\"\n", 1, 1, "analyses[0]",
     "one of speed_rpm or (speed_start_rpm, speed_stop_rpm, speed_count)", "none of them"},
    {"TabulatedLengthMismatch",
     "[[bearings]]\nnode = \"rotor.0\"\nspeed_rpm = [0, 1000, 2000]\nkxx = [1e6, 2e6]\n", 4, 7,
     "bearings[0].kxx", "3 values, one per 'speed_rpm' entry", "2 values"},
    {"TabulatedWithoutSpeeds", "[[bearings]]\nnode = \"rotor.0\"\nkxx = [1e6, 2e6]\n", 3, 7,
     "bearings[0].kxx", "a single value", "2 values", "give 'speed_rpm'"},
    {"OverlappingBands",
     "[damping]\n[[damping.bands]]\nf_min_hz = 0\nf_max_hz = 200\nratio = 0.01\n"
     "[[damping.bands]]\nf_min_hz = 100\nf_max_hz = 400\nratio = 0.1\n",
     7, 12, "damping.bands[1].f_min_hz", "does not overlap damping.bands[0]", "100 Hz"},

    // --- references and names ---
    {"UndefinedStation", "[[point_masses]]\nnode = \"rotor.9\"\nmass = 1\n", 2, 8,
     "point_masses[0].node", "a station of shaft 'rotor': \"rotor.0\" to \"rotor.4\"",
     "\"rotor.9\""},
    {"UndefinedShaftInNode", "[[point_masses]]\nnode = \"rotr.1\"\nmass = 1\n", 2, 8,
     "point_masses[0].node", "a node", "there is no shaft 'rotr'", "did you mean 'rotor'?"},
    {"UndefinedFreeNode",
     "[[nodes]]\nname = \"housing\"\nposition = [0, 1, 0]\n[[bearings]]\nnode = \"rotor.0\"\n"
     "node2 = \"housng\"\nkxx = 1e6\n",
     6, 9, "bearings[0].node2", "a node", "\"housng\"", "did you mean 'housing'?"},
    {"UndefinedMaterial",
     "[[shafts.elements]]\nlength = 0.1\nouter_diameter = 0.05\n"
     "material = \"stee1\"\n",
     4, 12, "shafts[0].elements[1].material", "a material name ('steel')", "\"stee1\"",
     "did you mean 'steel'?"},
    {"DuplicateName",
     "[[materials]]\nname = \"steel\"\nyoungs_modulus = 1e11\nshear_modulus = 4e10\n"
     "density = 7000\n",
     2, 8, "materials[1].name", "a name not used by another of [[materials]]",
     "already the name of materials[0]", "first defined at model.toml:2"},
    {"DrivenByCycle",
     "[[shafts]]\nname = \"a\"\nmaterial = \"steel\"\ndriven_by = \"b\"\ngear_ratio = 2\n"
     "[[shafts.elements]]\nlength = 1\nouter_diameter = 0.1\n"
     "[[shafts]]\nname = \"b\"\nmaterial = \"steel\"\ndriven_by = \"a\"\ngear_ratio = 0.5\n"
     "[[shafts.elements]]\nlength = 1\nouter_diameter = 0.1\n",
     12, 13, "shafts[2].driven_by", "a chain of driven_by", "the cycle a -> b -> a"},
    {"DrivenWithoutRatio",
     "[[shafts]]\nname = \"b\"\nmaterial = \"steel\"\ndriven_by = \"rotor\"\n"
     "[[shafts.elements]]\nlength = 1\nouter_diameter = 0.1\n",
     1, 1, "shafts[1].gear_ratio", "the key 'gear_ratio'", "'driven_by' without 'gear_ratio'"},
    {"UnknownSensorInAnalysis",
     "[[analyses]]\nname = \"h\"\ntype = \"harmonic\"\nfrequency_start_hz = 1\n"
     "frequency_stop_hz = 10\ninput_node = \"rotor.2\"\nsensors = [\"tip\"]\n",
     7, 12, "analyses[0].sensors[0]", "a sensor name, but there is no [[sensors]] table",
     "\"tip\""},
    {"UnknownForceInAnalysis",
     "[[forces]]\nname = \"mesh_force\"\nnode = \"rotor.1\"\ndof = \"uy\"\namplitude = 10\n"
     "[[analyses]]\nname = \"h\"\ntype = \"harmonic\"\nfrequency_start_hz = 1\n"
     "frequency_stop_hz = 10\nforces = [\"mesh_forc\"]\n",
     11, 11, "analyses[0].forces[0]", "a force name ('mesh_force')", "\"mesh_forc\"",
     "did you mean 'mesh_force'?"},
    {"UnbalanceAnalysisWithoutUnbalances",
     "[[analyses]]\nname = \"u\"\ntype = \"unbalance\"\nspeed_rpm = [1000]\n", 3, 8,
     "analyses[0].type", "an analysis type whose excitation exists",
     "the model has no [[unbalances]]"},
    {"UnbalanceOnStillNode",
     "[[nodes]]\nname = \"hub\"\nposition = [0, 1, 0]\n[[unbalances]]\nnode = \"hub\"\n"
     "mass_eccentricity = 1e-4\n",
     5, 8, "unbalances[0].node", "a spinning node", "does not spin"},
    {"SweepTargetMissing",
     "[[analyses]]\nname = \"modes\"\ntype = \"modal\"\n[[analyses]]\nname = \"s\"\n"
     "type = \"sweep\"\nparameter = \"shafts[0].elements[0].length\"\nvalues = [0.4, 0.5]\n"
     "analysis = \"mode\"\n[[analyses.outputs]]\nquantity = \"natural_frequency\"\n",
     9, 12, "analyses[1].analysis", "an analysis name ('modes', 's')", "\"mode\"",
     "did you mean 'modes'?"},
    {"SweepOfSweep",
     "[[analyses]]\nname = \"a\"\ntype = \"sweep\"\nparameter = \"shafts[0].elements[0].length\"\n"
     "values = [0.4]\nanalysis = \"b\"\n[[analyses.outputs]]\nquantity = \"natural_frequency\"\n"
     "[[analyses]]\nname = \"b\"\ntype = \"sweep\"\nparameter = \"shafts[0].elements[0].length\"\n"
     "values = [0.4]\nanalysis = \"a\"\n[[analyses.outputs]]\nquantity = \"natural_frequency\"\n",
     6, 12, "analyses[0].analysis", "an analysis that is not a sweep", "\"b\", a sweep"},
    {"SweepParameterUnknownKey",
     "[[bearings]]\nnode = \"rotor.0\"\nkxx = 1e6\n[[analyses]]\nname = \"modes\"\n"
     "type = \"modal\"\n[[analyses]]\nname = \"s\"\ntype = \"sweep\"\n"
     "parameter = \"bearings[0].kxy2\"\nvalues = [1e6]\nanalysis = \"modes\"\n"
     "[[analyses.outputs]]\nquantity = \"natural_frequency\"\n",
     10, 13, "bearings[0].kxy2", "a key of [[bearings]]", "the unknown key 'kxy2'",
     "did you mean 'kxy'?"},
    {"SweepParameterNotNumeric",
     "[[analyses]]\nname = \"modes\"\ntype = \"modal\"\n[[analyses]]\nname = \"s\"\n"
     "type = \"sweep\"\nparameter = \"shafts[0].theory\"\nvalues = [1]\nanalysis = \"modes\"\n"
     "[[analyses.outputs]]\nquantity = \"natural_frequency\"\n",
     7, 13, "shafts[0].theory", "the path of a number or integer key", "'theory', which is one of"},
    {"SweepOutputDoesNotFitTarget",
     "[[sensors]]\nname = \"tip\"\nnode = \"rotor.4\"\ndof = \"ux\"\n"
     "[[analyses]]\nname = \"modes\"\ntype = \"modal\"\n[[analyses]]\nname = \"s\"\n"
     "type = \"sweep\"\nparameter = \"shafts[0].elements[0].length\"\nvalues = [0.4]\n"
     "analysis = \"modes\"\n[[analyses.outputs]]\nquantity = \"peak_amplitude\"\nsensor = "
     "\"tip\"\n",
     15, 12, "analyses[1].outputs[0].quantity", "an output of a harmonic or unbalance",
     "\"peak_amplitude\" for analysis 'modes' of type \"modal\""},
    {"SweepIntegerKeyFractionalValue",
     "[[analyses]]\nname = \"modes\"\ntype = \"modal\"\n[[analyses]]\nname = \"s\"\n"
     "type = \"sweep\"\nparameter = \"shafts[0].elements[0].divisions\"\nvalues = [2, 2.5]\n"
     "analysis = \"modes\"\n[[analyses.outputs]]\nquantity = \"natural_frequency\"\n",
     8, 10, "analyses[1].values", "integers, since shafts[0].elements[0].divisions is an integer",
     "2.5"},
    {"GearsAtSamePlace",
     "[[nodes]]\nname = \"g\"\nposition = [0, 0, 0]\n[[gear_meshes]]\ngear1 = \"rotor.0\"\n"
     "gear2 = \"g\"\nbase_radius1 = 0.1\nbase_radius2 = 0.1\nstiffness = 1e8\n",
     6, 9, "gear_meshes[0].gear2", "a gear node away from gear1's node",
     "at the same position as \"rotor.0\"", "give mesh_direction"},
};

INSTANTIATE_TEST_SUITE_P(AllClasses, ModelErrors, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<ErrorCase>& case_info) {
                           return std::string(case_info.param.name);
                         });

TEST(ModelErrorsFile, MissingFileIsAnInputError) {
  try {
    (void)analyses::load_document("/nonexistent/model.toml");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "/nonexistent/model.toml");
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos);
  }
}

TEST(ModelErrorsFile, EveryListedErrorPointsIntoTheFile) {
  // A sanity check of the table itself: each case's location is inside its text.
  for (const auto& c : kCases) {
    const std::string text = c.whole ? c.text : kBase + c.text;
    const int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
    const int line = c.whole ? c.line : kBaseLines + c.line;
    EXPECT_LE(line, lines) << c.name;
  }
}

}  // namespace
}  // namespace geardyn::model
