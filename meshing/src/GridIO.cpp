#include <strata/meshing/GridIO.h>

#include <strata/AtomicFile.h>
#include <strata/Error.h>

#include <openvdb/io/File.h>

namespace strata::meshing {

void writeGrid(const openvdb::FloatGrid& grid, const std::filesystem::path& path)
{
    openvdb::initialize();
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        try {
            openvdb::io::File file(temporary.string());
            openvdb::GridCPtrVec grids;
            // io::File takes shared pointers; the copy shares the tree (no deep copy).
            grids.push_back(grid.copy());
            file.write(grids);
            file.close();
        } catch (const openvdb::Exception& e) {
            throw Error("cannot write VDB file '" + path.string() + "': " + e.what());
        }
    });
}

openvdb::FloatGrid::Ptr readLevelSet(const std::filesystem::path& path)
{
    openvdb::initialize();
    const std::string where = "VDB file '" + path.string() + "'";
    if (!std::filesystem::exists(path)) {
        throw Error(where + " does not exist");
    }
    openvdb::GridPtrVecPtr grids;
    try {
        openvdb::io::File file(path.string());
        file.open(/*delayLoad*/ false);
        grids = file.getGrids();
        file.close();
    } catch (const std::exception& e) {
        throw Error(where + " is not a readable OpenVDB file: " + e.what());
    }
    if (!grids || grids->empty()) {
        throw Error(where + " holds no grid");
    }
    openvdb::FloatGrid::Ptr grid;
    for (const openvdb::GridBase::Ptr& base : *grids) {
        if ((grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base))) break;
    }
    if (!grid) {
        throw Error(where + " holds no float grid (found '" + grids->front()->type() + "')");
    }
    if (grid->getGridClass() != openvdb::GRID_LEVEL_SET) {
        throw Error(where + ": grid '" + grid->getName() + "' is not a level set (class '" +
                    openvdb::GridBase::gridClassToString(grid->getGridClass()) + "')");
    }
    if (!grid->hasUniformVoxels() || !grid->transform().isLinear()) {
        throw Error(where + ": grid '" + grid->getName() + "' needs a linear transform with cubic voxels");
    }
    if (grid->activeVoxelCount() == 0) {
        throw Error(where + ": grid '" + grid->getName() + "' is empty (no active voxels)");
    }
    return grid;
}

} // namespace strata::meshing
