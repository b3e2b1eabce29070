"""Writers of the test vectors in shared_schema/vectors/, which hold the Python code and its
TypeScript twin to the same numbers. Each module writes the file of its name
(`python -m holiscene.twin_vectors.room_fit` writes shared_schema/vectors/room_fit.json).
They run the backend, so they live here and not in the contract package."""
