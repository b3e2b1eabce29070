// Generated from shared_schema/jsonschema/vocabulary.json by ts/generate.mjs. Do not edit.
export const NYU40_CLASSES = ["wall","floor","cabinet","bed","chair","sofa","table","door","window","bookshelf","picture","counter","blinds","desk","shelves","curtain","dresser","pillow","mirror","floor_mat","clothes","ceiling","books","refrigerator","television","paper","towel","shower_curtain","box","whiteboard","person","night_stand","toilet","sink","lamp","bathtub","bag","otherstructure","otherfurniture","otherprop"] as const;
export const STRUCTURAL_SUPPORTERS = ["ceiling","floor","wall"] as const;
export const SUPPORT_TYPES = ["below","behind"] as const;
