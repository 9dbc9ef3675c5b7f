//! The peer renderers' benchmark scenes (`tests/data/peers/*.rib`, see the README there) read
//! without an error or a warning, with the requests each is known to hold.

use std::path::PathBuf;

use reyes_rib::{Reader, RequestKind};

/// The peers' scenes, kept with the tests.
fn peers() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/peers")
}

#[test]
fn peer_scenes_read_cleanly() {
    let dir = peers();
    let mut read = 0;
    for (file, spheres, motion, solids) in [
        ("csg.rib", 4, 0, 6),
        ("a_balls.rib", 16, 0, 0),
        ("b_balls_mb.rib", 16, 16, 0),
        ("c_balls_dof.rib", 16, 0, 0),
        ("d_heavy_mb.rib", 400, 400, 0),
    ] {
        let path = dir.join(file);
        let mut r = Reader::open(&path).unwrap_or_else(|e| panic!("{e}"));
        let mut kinds = Vec::new();
        while let Some(q) = r.next_request().unwrap_or_else(|e| panic!("{e}")) {
            if q.kind == RequestKind::LightSource {
                assert!(q.param("intensity").and_then(|p| p.floats()).is_some(), "{}", q.at);
            }
            kinds.push(q.kind);
        }
        assert_eq!(r.warnings(), &[], "{file}");
        let count = |k| kinds.iter().filter(|&&x| x == k).count();
        assert_eq!(count(RequestKind::Sphere), spheres, "{file}");
        assert_eq!(count(RequestKind::MotionBegin), motion, "{file}");
        assert_eq!(count(RequestKind::SolidBegin), solids, "{file}");
        assert_eq!(count(RequestKind::WorldBegin), 1, "{file}");
        assert_eq!(kinds.last(), Some(&RequestKind::WorldEnd), "{file}");
        read += 1;
    }
    assert_eq!(read, 5);
}

#[test]
fn peer_depth_of_field_and_camera() {
    let dir = peers();
    let all: Vec<_> =
        Reader::open(dir.join("c_balls_dof.rib")).unwrap().map(Result::unwrap).collect();
    let dof = all.iter().find(|q| q.kind == RequestKind::DepthOfField).expect("DepthOfField");
    assert_eq!((dof.float(0), dof.float(1), dof.float(2)), (Some(2.8), Some(1.0), Some(8.0)));
    let proj = all.iter().find(|q| q.kind == RequestKind::Projection).unwrap();
    assert_eq!(proj.string(0), Some("perspective"));
    assert_eq!(proj.param("fov").and_then(|p| p.floats()), Some(&[45.0][..]));
    let format = all.iter().find(|q| q.kind == RequestKind::Format).unwrap();
    assert_eq!((format.int(0), format.int(1)), (Some(640), Some(480)));
}
