//! NEAT, CPPNs, neural networks and HyperNEAT substrate decoding.
