#pragma once
// The SID files the model-file targets' inputs may name for a flexible body, written once into
// the scratch folder: "chain.sid.h5" (a clamped synthetic chain with stiffening) and
// "rod.sid.h5" (a free one), 11 points and 4 modes each, as ffr-synth writes them.
#include "scratch.hpp"

#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/synthetic.hpp"

namespace ffr::fuzz {

inline void write_chain_sids() {
  namespace syn = ffr::formats::synthetic;
  syn::ChainParams p;
  p.points = 11;
  p.modes = 4;
  p.clamped = true;
  p.stiffening = true;
  ffr::formats::write_sid(syn::spring_chain(p).sid, scratch() / "chain.sid.h5");
  p.clamped = false;
  p.stiffening = false;
  ffr::formats::write_sid(syn::spring_chain(p).sid, scratch() / "rod.sid.h5");
}

}  // namespace ffr::fuzz
