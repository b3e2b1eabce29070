"""Learned support inference: preprocessing, the Relation Networks, training, ONNX runtime.

Only `train`, `nets` and `export` import PyTorch (the `train` extra); everything the server and
`holiscene infer` use runs on numpy and onnxruntime.
"""
