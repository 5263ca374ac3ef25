// Which wedge owns a tetrahedron while an added point is split
// (point_splitting.cpp): the ball's tetrahedra, and those a wedge takes in
// as it grows (up to thousands toward a target). Asked several times for
// every face a growth looks at, so a hash table (a std::map's pointer
// chase and node allocations were most of the growth's own time); listed
// in increasing id order, as the std::map it replaces was, so the
// tetrahedra handed to replace_tets, and the mesh made, stay the same.
#pragma once

#include <algorithm>
#include <vector>

#include "mesh/key_table.hpp"
#include "mesh/tet_mesh.hpp"

namespace cbr::recover {

class TetOwners {
public:
    // The owner of t, or nullptr.
    const int* find(mesh::TetId t) const { return table_.find(t); }
    bool contains(mesh::TetId t) const { return find(t) != nullptr; }
    // t must not be listed yet.
    void add(mesh::TetId t, int owner) {
        table_[t] = owner;
        ids_.push_back(t);
    }
    // The tetrahedra listed, in the order added.
    const std::vector<mesh::TetId>& ids() const { return ids_; }
    // The same in increasing id order.
    std::vector<mesh::TetId> sorted_ids() const {
        std::vector<mesh::TetId> ids = ids_;
        std::sort(ids.begin(), ids.end());
        return ids;
    }

private:
    mesh::KeyTable<int> table_;
    std::vector<mesh::TetId> ids_;  // in the order added
};

}  // namespace cbr::recover
