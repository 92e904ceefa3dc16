// The compiled part of the Python package `myoshell` (python/myoshell/__init__.py re-exports it).
#include "bindings.h"

PYBIND11_MODULE(_myoshell, m) {
  m.doc() = "Myoshell: physically based animation of human faces (compiled part; import myoshell).";
  myo::python::bindErrors(m);
  myo::python::bindHeads(m);
  myo::python::bindFace(m);
  myo::python::bindSimulator(m);
  myo::python::bindScenePlayer(m);
  myo::python::bindRigs(m);
  myo::python::bindRigMaking(m);
  myo::python::bindRigFitting(m);
  myo::python::bindDrive(m);
  myo::python::bindExports(m);
  myo::python::bindThreads(m);
  myo::python::bindLive(m);
}
