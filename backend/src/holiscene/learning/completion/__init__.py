"""Shape completion from an object's partial depth points (thesis Ch. 6, SK-PCN, a smaller variant).

`scans.py` makes training pairs from the furniture library (a partial depth scan from a random
view; dense surface samples and meso-skeleton points as targets), `net.py` and `train.py` the
network and its training (PyTorch, never imported at run time), `runtime.py` the ONNX model
on onnxruntime, `meshing.py` a mesh from the completed points. Points live in the normalised
object frame: the object's 3D box mapped onto the cube [-0.5, 0.5]^3 (x front, y up, z right).
"""
