// normal_load_mu: the friction coefficient depends on the normal load.
#pragma once

#include "effect.hpp"

namespace stickslip::identify {

// μ(t_N) = μ + dμ/dt_N (t_N − t_N,ref); t_N,ref is the mean load of the dataset so that μ
// keeps its meaning of the coefficient at a typical load.
struct NormalLoadMu {
    double dmu_dtN_per_N = 0.0;  // dμ/dt_N [1/N]

    double muShift(double tN_N, double tNref_N) const { return dmu_dtN_per_N * (tN_N - tNref_N); }

    static EffectInfo info() {
        return {"normal_load_mu",
                "The coefficient of friction changes with the normal load (real contact area grows "
                "less than proportionally with load, surface films break through at high pressure), "
                "so runs at different t_N need different mu. The paper's law takes the force "
                "proportional to t_N with one mu for every load.",
                "Residual whose mean level during slip differs from run to run in step with t_N: it "
                "correlates with t_N and with the run index, not with V inside a run.",
                {{"dmu_dtN_per_N", "1/N", 0.0, -0.1, 0.1, false, 0.0, true}},
                {"tN", "run_index"},
                {true, true}};
    }
};

}  // namespace stickslip::identify
