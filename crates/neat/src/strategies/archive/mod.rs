//! The archives the strategies keep, apart from how they breed: MAP-Elites'
//! cells ([`grid`] and [`cvt`]) and elites ([`elites`]), NSGA-II's Pareto
//! ranking ([`pareto`]) and novelty search's archive ([`novelty`]) with its
//! k-nearest-neighbour search ([`knn`]).

pub mod cvt;
pub mod elites;
pub mod grid;
pub mod knn;
pub mod novelty;
pub mod pareto;
