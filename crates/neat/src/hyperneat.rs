//! HyperNEAT: decoding a CPPN into a substrate controller.
