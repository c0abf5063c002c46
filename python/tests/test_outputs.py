"""Python outputs never overwrite inputs: Mesh.render and Mesh.save (the methods that write files)
refuse a target that is the mesh's own file, however it is named (the same path, a symbolic or
hard link, another spelling, a file named by content), before any work and writing nothing;
render writes .png names only. The issue: `m = trigeo.load('spot.obj'); m.render('spot.obj')`
replaced the mesh with a PNG."""
import os
import shutil

import numpy as np
import pytest

import trigeo
from conftest import SPOT


@pytest.fixture
def mesh_file(tmp_path):
    p = tmp_path / "spot.obj"
    shutil.copyfile(SPOT, p)
    return p


def _refused(call, path, before, folder):
    listing = sorted(os.listdir(folder))
    with pytest.raises(trigeo.InvalidArgumentError, match="own file") as e:
        call()
    assert path.read_bytes() == before, f"{path} changed"
    assert sorted(os.listdir(folder)) == listing, f"files appeared: {sorted(os.listdir(folder))} (was {listing})"
    return str(e.value)


def test_render_onto_the_mesh_is_refused(mesh_file, tmp_path):
    """The issue's case, with a .png-named target being the mesh: render refuses a non-.png
    name first (as trigeo render -o x.jpg)."""
    before = mesh_file.read_bytes()
    m = trigeo.load(mesh_file)
    with pytest.raises(trigeo.InvalidArgumentError, match=r"\.png"):
        m.render(mesh_file)
    assert mesh_file.read_bytes() == before
    png = tmp_path / "spot.png"  # the same mesh under a .png name, loaded by content
    shutil.copyfile(mesh_file, png)
    mp = trigeo.load(png, format="obj")
    msg = _refused(lambda: mp.render(png, width=32, height=24), png, before, tmp_path)
    assert str(png) in msg, msg


@pytest.mark.parametrize("how", ["same", "symlink", "hardlink", "spelling", "relative"])
def test_outputs_onto_the_mesh_through_any_name_are_refused(mesh_file, tmp_path, monkeypatch, how):
    before = mesh_file.read_bytes()
    m = trigeo.load(mesh_file)
    for ext, call in ((".obj", lambda t: m.save(t)),
                      (".ply", lambda t: m.save(t, fields={"d": np.zeros(m.vertex_count)})),
                      (".png", lambda t: m.render(t, width=32, height=24))):
        if how == "same":
            if ext != ".obj":
                continue
            target = mesh_file
        elif how == "symlink":
            target = tmp_path / f"link{ext}"
            target.symlink_to(mesh_file)
        elif how == "hardlink":
            target = tmp_path / f"hard{ext}"
            os.link(mesh_file, target)
        elif how == "spelling":
            if ext != ".obj":
                continue
            (tmp_path / "sub").mkdir(exist_ok=True)
            target = tmp_path / "sub" / ".." / "spot.obj"
        else:
            if ext != ".obj":
                continue
            monkeypatch.chdir(tmp_path)
            target = "spot.obj"
        _refused(lambda: call(target), mesh_file, before, tmp_path)


def test_mesh_file_replaced_after_loading_is_still_refused(mesh_file, tmp_path):
    """What the mesh's path names now is refused too (the file it was loaded from, moved away,
    and a new file at its path)."""
    m = trigeo.load(mesh_file)
    os.rename(mesh_file, tmp_path / "old.obj")
    shutil.copyfile(tmp_path / "old.obj", mesh_file)
    before = mesh_file.read_bytes()
    _refused(lambda: m.save(mesh_file), mesh_file, before, tmp_path)
    _refused(lambda: m.save(tmp_path / "old.obj"), tmp_path / "old.obj", before, tmp_path)


def test_other_targets_are_written(mesh_file, tmp_path):
    """The check refuses the mesh only: other files are replaced whole, a mesh from arrays
    writes anywhere, and a .PNG name is a PNG name."""
    m = trigeo.load(mesh_file)
    (tmp_path / "old.png").write_bytes(b"old")
    m.render(tmp_path / "old.png", width=32, height=24)
    m.render(tmp_path / "UPPER.PNG", width=32, height=24)
    m.save(tmp_path / "copy.ply")
    arrays = trigeo.Mesh(np.array(m.vertices), np.array(m.faces))
    assert arrays.source is None
    arrays.save(tmp_path / "copy.obj")
    for name in ("old.png", "UPPER.PNG"):
        assert (tmp_path / name).read_bytes()[:4] == b"\x89PNG", name
    assert trigeo.load(tmp_path / "copy.obj").vertex_count == m.vertex_count
    assert sorted(os.listdir(tmp_path)) == ["UPPER.PNG", "copy.obj", "copy.ply", "old.png", "spot.obj"]


@pytest.mark.parametrize("name", ["x.jpg", "x.png.txt", "x", "x.obj"])
def test_render_writes_png_names_only(mesh_file, tmp_path, name):
    m = trigeo.load(mesh_file)
    with pytest.raises(trigeo.InvalidArgumentError, match=r"\.png"):
        m.render(tmp_path / name, width=32, height=24)
    assert sorted(os.listdir(tmp_path)) == ["spot.obj"]
