"""Fetch the front-end files the offline book serves itself: `python tools/vendor.py DEST`.

A pinned npm package, downloaded from the npm registry (or $NPM_REGISTRY), checked by SHA-256,
and unpacked with the standard library only, so the set-up works on Linux and macOS: MathJax 3,
one component (tex-mml-chtml.js) and its woff-v2 fonts. (The explorers need no widget embedder:
the book's own player draws them, book/_assets/ddg-player.js.)

DEST (the Makefile uses .venv/vendor) is listed in `html_static_path` in _config.yml, so the
book build copies it into _build/html/_static.
"""

import fnmatch
import hashlib
import io
import os
import pathlib
import shutil
import sys
import tarfile
import urllib.request

REGISTRY = os.environ.get("NPM_REGISTRY", "https://registry.npmjs.org").rstrip("/")

# (folder in DEST, tarball path in the registry, sha256, files to keep, their prefix to strip)
PACKAGES = [
    ("mathjax", "mathjax/-/mathjax-3.2.2.tgz",
     "1b9c0a1c44df864e915690558e72adb9cc5203360daefd385084ced3b6c64c09",
     ["package/es5/tex-mml-chtml.js", "package/es5/output/chtml/fonts/woff-v2/*"], "package/es5/"),
]


def download(path):
    with urllib.request.urlopen(f"{REGISTRY}/{path}", timeout=120) as response:
        return response.read()


def unpack(data, folder, keep, prefix):
    """Write the members of the tarball ``data`` that match ``keep`` into ``folder``, minus ``prefix``."""
    count = 0
    with tarfile.open(fileobj=io.BytesIO(data), mode="r:gz") as tar:
        for member in tar.getmembers():
            wanted = any(fnmatch.fnmatch(member.name, pattern) for pattern in keep)
            if not member.isfile() or not wanted:
                continue
            target = folder / member.name.removeprefix(prefix)
            if ".." in pathlib.PurePosixPath(member.name).parts:
                raise ValueError(f"unsafe path in the tarball: {member.name}")
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(tar.extractfile(member).read())
            count += 1
    return count


def main(dest):
    dest = pathlib.Path(dest)
    shutil.rmtree(dest, ignore_errors=True)
    for folder, path, sha256, keep, prefix in PACKAGES:
        data = download(path)
        digest = hashlib.sha256(data).hexdigest()
        if digest != sha256:
            sys.exit(f"error: {path} has SHA-256 {digest}, expected {sha256}: not using it")
        count = unpack(data, dest / folder, keep, prefix)
        print(f"{path}: checked, {count} files in {dest / folder}")
    (dest / ".installed").touch()


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".venv/vendor")
