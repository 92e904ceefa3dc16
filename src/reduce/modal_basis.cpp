#include "myoshell/reduce/modal_basis.h"

#include "myoshell/core/check.h"

namespace myo {

size_t ModalBasis::memoryBytes() const {
  return sizeof(double) * (Phi.size() + Psi.size() + lambda.size() + freeMass.size()) +
         sizeof(int) * freeVertices.size();
}

std::vector<int> ModalBasis::fullToFree() const {
  std::vector<int> map(fullVertexCount, -1);
  for (int i = 0; i < freeCount(); ++i) map[freeVertices[i]] = i;
  return map;
}

MatX3 scatterToFull(const ModalBasis& basis, const MatX3& freeField) {
  MYO_CHECK_EQ(freeField.rows(), static_cast<Eigen::Index>(basis.freeCount()));
  MatX3 full = MatX3::Zero(basis.fullVertexCount, 3);
  for (int i = 0; i < basis.freeCount(); ++i) full.row(basis.freeVertices[i]) = freeField.row(i);
  return full;
}

MatX3 gatherFree(const ModalBasis& basis, const MatX3& fullField) {
  MYO_CHECK_EQ(fullField.rows(), static_cast<Eigen::Index>(basis.fullVertexCount));
  MatX3 out(basis.freeCount(), 3);
  for (int i = 0; i < basis.freeCount(); ++i) out.row(i) = fullField.row(basis.freeVertices[i]);
  return out;
}

}  // namespace myo
