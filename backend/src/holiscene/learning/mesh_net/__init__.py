"""The mesh generation network (thesis Ch. 5, MGN, a smaller variant): each object's mesh as its
class's template deformed by a network that reads the object's silhouette, with the faces it
expects to be wrong cut away (the thesis's topology modification)."""
