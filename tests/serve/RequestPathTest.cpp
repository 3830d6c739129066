// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/serve/RequestPath.h>

#include "HttpTestUtil.h"
#include "TestDir.h"

#include <gtest/gtest.h>

namespace fs = std::filesystem;
using strata::serve::resolveRequestPath;

namespace {

// root/ holds a.glb, viewer/index.html, empty/; secret.txt lies beside root.
struct Tree
{
    fs::path top = strata::test::freshTestDir();
    fs::path root = top / "bake";
    fs::path canonicalRoot;
    Tree()
    {
        strata::test::writeFile(root / "a.glb", "glb");
        strata::test::writeFile(root / "viewer" / "index.html", "<html>");
        fs::create_directories(root / "empty");
        strata::test::writeFile(top / "secret.txt", "secret");
        strata::test::writeFile(top / "bake2" / "secret.txt", "secret");
        canonicalRoot = fs::canonical(root);
    }
};

} // namespace

TEST(RequestPath, FilesAndFolderIndexesInsideTheRoot)
{
    const Tree tree;
    const auto a = resolveRequestPath(tree.canonicalRoot, "/a.glb");
    EXPECT_EQ(a.status, 200);
    EXPECT_EQ(a.file, tree.canonicalRoot / "a.glb");
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "//./a.glb").status, 200);
    const auto index = resolveRequestPath(tree.canonicalRoot, "/viewer/");
    EXPECT_EQ(index.status, 200);
    EXPECT_EQ(index.file, tree.canonicalRoot / "viewer" / "index.html");
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "/viewer").status, 301);
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "/empty/").status, 404);
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "/missing.glb").status, 404);
}

TEST(RequestPath, WaysOutAreRefused)
{
    const Tree tree;
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "/../secret.txt").status, 403);
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "/viewer/../../secret.txt").status, 403);
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "/viewer/../a.glb").status, 403); // even when it stays inside
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "/..").status, 403);
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "/..\\secret.txt").status, 403);
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, std::string_view("/a.glb\0.png", 11)).status, 400);
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "a.glb").status, 400);
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "").status, 400);
    // An absolute path is a path under the root, not the file system's.
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, (tree.top / "secret.txt").string()).status, 404);
}

TEST(RequestPath, SymlinksAreFollowedOnlyWhenTheyStayInside)
{
    const Tree tree;
    fs::create_symlink("a.glb", tree.root / "inside.glb");
    fs::create_directory_symlink("viewer", tree.root / "viewer-link");
    fs::create_symlink("../secret.txt", tree.root / "outside.txt");
    fs::create_directory_symlink("..", tree.root / "up");
    fs::create_symlink("../bake2/secret.txt", tree.root / "sibling.txt"); // shares the root's name as a prefix
    fs::create_symlink("nowhere", tree.root / "dangling");
    fs::create_symlink("loop", tree.root / "loop");

    const auto inside = resolveRequestPath(tree.canonicalRoot, "/inside.glb");
    EXPECT_EQ(inside.status, 200);
    EXPECT_EQ(inside.file, tree.canonicalRoot / "a.glb");
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "/viewer-link/").status, 200);
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "/outside.txt").status, 403);
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "/up/secret.txt").status, 403);
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "/sibling.txt").status, 403);
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "/dangling").status, 404);
    EXPECT_EQ(resolveRequestPath(tree.canonicalRoot, "/loop").status, 404);
}
