// Selection test (4) of the identify loop, the simulated null (simulated_null.cpp says what it
// is; IdentifyOptions::simulatedNullReplicas how it is used). Internal to the loop.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "identify_internal.hpp"

namespace stickslip::identify::detail {

// A replica of `run`'s recording made from the model (spec, vals): the model simulated over the
// recorded drive (its harmonic fit, from a pre-roll of 3 s), every model-made channel given
// white noise at the recording's own level (dsp::whiteNoiseRms) and the force the mains pickup
// fitted to the recorded force; the other channels (time, stage, loads) as recorded. Dynamics
// runs. False with `why` when the recording lacks a channel or the simulation fails.
bool replicaRecording(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals,
                      const IdentifyRun& run, uint64_t seed, io::Run& out, std::string& why);

struct SimulatedNull {
    bool ran = false;
    std::vector<double> gains;  // per replica: SS of the current model's refit − the candidate's (sorted)
    std::string note;           // why it did not run
    std::map<std::string, double> model;  // the model the null's replicas were made from (bias-corrected)
};

// `replicas` replicas of the fit runs from the current model, each cleaned by
// IdentifyOptions::reprepare and prepared as the data were; on each, the current model and the
// candidate (cand) are refitted from their fits to the data (curVals, candVals). The replicas'
// model is curVals corrected by the fit's own bias, measured on max(2, replicas/2) replicas of
// curVals refitted (one step of indirect inference: the model whose fits land where the data's did).
SimulatedNull simulatedGainNull(const Context& cx, const Spec& cur, const std::map<std::string, double>& curVals,
                                const Spec& cand, const std::map<std::string, double>& candVals,
                                const std::vector<size_t>& fitIdx, int replicas, uint64_t seed, long& fits);

}  // namespace stickslip::identify::detail
