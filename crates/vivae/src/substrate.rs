//! The polar substrate layout of the driving controller.
