#pragma once
// What the analyses of solid components share in their settings: how a solid (or one sector of
// it) is reduced before the solve (cyclic_modal, reduction, cyclic_forced_response).

namespace geardyn::analyses {

/// Reduction of a solid before the solve: none, Guyan (static) or Craig-Bampton (static plus
/// fixed-interface modes).
enum class ReductionMethod { None, Guyan, CraigBampton };

}  // namespace geardyn::analyses
