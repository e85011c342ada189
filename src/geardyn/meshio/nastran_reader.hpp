#pragma once
// Reader for Nastran bulk data (MSC / NX / Simcenter syntax): the solid mesh, concentrated
// masses, scalar springs, rigid and averaging connections and single-point constraints of a
// model, as solid::Mesh.
//
// Units: Nastran has none; the numbers are taken as they stand and geardyn reads them as SI
// (m, kg, N, Pa, kg/m^3). A deck in mm-t-s or inches must be converted before it is read.
//
// Supported entries
//   GRID           ID CP X1 X2 X3 CD PS (SEID must be blank or 0). Positions in the CP system
//                  are converted to global (basic) coordinates. DOF components of the node refer
//                  to its CD system; geardyn applies components in global axes, so a card that
//                  names components of a node whose CD axes are rotated (CELAS excepted, below)
//                  must name whole sets
//                  (translations 123 all or none, rotations 456 all or none), otherwise it is an
//                  InputError. PS becomes a Constraint.
//   CORD2R/C/S     CID RID A B C, chained through RID to any depth (cycles are errors).
//   CTETRA         4 or 10 grids; CHEXA 8 or 20; CPENTA 6 or 15 (all mid-edge grids or none).
//                  Connectivity is converted to Gmsh's node order (element_ordering.hpp) and
//                  mirrored where the given order has a negative volume (Nastran accepts both).
//   PSOLID         PID MID (the other fields concern non-isotropic or fluid use and are ignored
//                  for isotropic MAT1). Elements of one PSOLID form the element set
//                  "PSOLID_<pid>".
//   MAT1           MID E G NU RHO. One blank of E, G, NU is derived from E = 2 (1 + NU) G; if
//                  only E (or only G) is given, NU and the other are 0 (Nastran's rule). A
//                  warning is issued when all three are given and |1 - E / (2 (1 + NU) G)| >
//                  0.01 (solids use E and NU). Solids need E > 0 and -1 < NU < 0.5.
//                  Material name "MAT1_<mid>".
//   CONM2          EID G CID M X1 X2 X3 / I11 I21 I22 I31 I32 I33. CID = 0: offset in global
//                  axes; CID = -1: X is the global position of the centre of gravity; CID > 0:
//                  offset and inertia in the local Cartesian axes of system CID at the grid.
//                  Inertia about the CG = [I11 -I21 -I31; -I21 I22 -I32; -I31 -I32 I33].
//   CELAS1 + PELAS EID PID G1 C1 G2 C2 / PID K GE S (two properties per PELAS entry).
//   CELAS2         EID K G1 C1 G2 C2 GE S. A blank grid grounds that end. GE is ignored with a
//                  warning (damping belongs to the model file). An end on a grid whose CD
//                  axes are rotated acts along that system's axis Ci at the grid (a spring
//                  with a direction, solid::Spring), e.g. radially for a cylindrical CD.
//   RBE2           EID GN CM GM1 ... (THRU allowed), optional trailing ALPHA.
//   RBE3           EID blank REFGRID REFC WT1 C1 G1,1 ... WT2 C2 G2,1 ...; the independent
//                  components Ci must be 123 (solid nodes). UM (or Ci other than 123) is reported
//                  as unsupported and the entry is skipped.
//   SPC1           SID C G1 G2 ... with "G1 THRU G2" ranges (grids missing inside a range are
//                  skipped, as Nastran does). Nodes of each set form the node set "SPC1_<sid>";
//                  the sets selected by NastranOptions::spc_set become Mesh::constraints.
//   ASET1/QSET1/BSET1/CSET1  C G1 G2 ... with "G1 THRU G2" ranges (grids missing inside a
//                  range are skipped), and ASET/QSET/BSET/CSET ID1 C1 ID2 C2 ...: the grids form
//                  the node sets "ASET", "QSET", "BSET", "CSET" (both forms of one letter add to
//                  one set). They name nodes (spiders, sensors, fixed_sets) and constrain nothing;
//                  the components are checked, not used.
//   SET (case control, between CEND and BEGIN BULK) "SET n = i1, i2 THRU i3 EXCEPT i4 ..."
//                  with continuation lines after a trailing comma: the GRID ids among the set's
//                  ids form the node set "SET_<n>" (a set naming no GRID, e.g. an element set,
//                  makes none, with a warning; ALL or real values are listed as unsupported).
//   INCLUDE        'file name' (quotes optional, the name may continue over several lines),
//                  resolved relative to the including file.
//   BEGIN BULK / ENDDATA: when the top file has a BEGIN BULK line, everything before it
//                  (executive and case control) is skipped; ENDDATA ends the deck.
// Every other entry is listed in NastranDeck::unsupported (name, file, line) and skipped, or
// raises an InputError when NastranOptions::unsupported_is_error.
//
// Formats: free field (commas; "NAME*" for large free field), small field (8 columns), large
// field (16 columns, "NAME*" / "*" continuation), tabs expanded to 8-column stops, continuation
// lines starting with '+', '*' or a blank first field (the marker in field 10 is not matched),
// comments from '$' to the end of the line, case-insensitive names. Real fields need a decimal
// point or an exponent, Nastran style: "1.5-3" = 1.5e-3, "2.+5" = 2e5, "1.E4", "1.0D3".
//
// Errors: a malformed field, a missing required field, an id that is not defined (grid,
// coordinate system, property, material) or defined twice raises InputError with the file, line
// and column of the field and key path "<CARD> field <n> (<name>)", where n counts the fields of
// the whole entry as Nastran does (1 = the name, 2..9 the first line, 10.. the continuations).
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/solid/mesh.hpp"

namespace geardyn::meshio {

struct NastranOptions {
  /// Raise InputError at the first entry the reader does not support, instead of listing it in
  /// NastranDeck::unsupported.
  bool unsupported_is_error = false;
  /// SPC1 set id whose constraints go to Mesh::constraints; 0: every SPC1 set. (Bulk data alone
  /// does not say which set the case control selects.) A set id that no SPC1 defines is an
  /// InputError. GRID PS constraints are always applied.
  long spc_set = 0;
  /// Follow INCLUDE statements (false: an INCLUDE is an InputError; for untrusted input).
  bool allow_include = true;
};

/// An entry the reader skipped.
struct UnsupportedCard {
  std::string name;    ///< entry name, upper case ("CQUAD4")
  std::string file;    ///< file it is in
  int line = 0;        ///< first line of the entry (1-based)
  std::string reason;  ///< why, when the entry type itself is supported (e.g. "RBE3 UM")
};

struct NastranDeck {
  solid::Mesh mesh;
  /// One message per value that was read but has no effect in geardyn, prefixed by file:line.
  std::vector<std::string> warnings;
  std::vector<UnsupportedCard> unsupported;
};

/// Reads the bulk data of the deck at `path` (and its INCLUDEs). Nodes are ordered by GRID id,
/// elements by element id. Throws InputError on bad input (see above).
NastranDeck read_nastran(const std::filesystem::path& path, const NastranOptions& options = {});

/// Same, from text in memory; `file_name` is used in messages and INCLUDEs are resolved relative
/// to its folder.
NastranDeck parse_nastran(std::string_view text, const std::string& file_name,
                          const NastranOptions& options = {});

/// Nastran real field: "1.5", "-.5", "1.", "1.5E-3", "1.5D-3", "1.5-3", "2.+5", "7E4".
/// Returns false if `text` is not one.
bool parse_nastran_real(std::string_view text, double& value);

}  // namespace geardyn::meshio
