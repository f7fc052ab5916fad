use super::*;
use crate::film::SampleValue;
use glam::Vec3;

fn checkpoint() -> Checkpoint {
    let settings = Settings::from_json(
        &serde_json::from_str(r#"{"width": 4, "height": 3, "spp": 64, "seed": 7}"#).unwrap(),
    )
    .unwrap();
    let mut film = Film::new(4, 3);
    for (i, p) in film.pixels.iter_mut().enumerate() {
        for _ in 0..i {
            p.add(&SampleValue {
                radiance: Vec3::new(0.3, 1.0 / 7.0, 2.5),
                ..Default::default()
            });
        }
    }
    let mut front = Map::new();
    front.insert("front".into(), "test".into());
    Checkpoint {
        settings,
        scene_hash: ContentHash([1, 2]),
        front,
        elapsed: Duration::from_millis(1500),
        film,
    }
}

#[test]
fn a_checkpoint_survives_the_trip_exactly() {
    let c = checkpoint();
    let bytes = c.to_bytes();
    assert_eq!(Checkpoint::from_bytes(&bytes), Ok(c.clone()));
    // The file is the film plus a small header: it does not grow with the
    // samples taken.
    let header = bytes.len() - c.film.pixels.len() * PIXEL_BYTES;
    assert!(header < 2048, "header of {header} bytes");
}

#[test]
fn truncated_or_corrupt_bytes_are_refused_by_message() {
    let bytes = checkpoint().to_bytes();
    for n in [0, 5, 8, 12, 20, bytes.len() / 2, bytes.len() - 1] {
        let err = Checkpoint::from_bytes(&bytes[..n]).unwrap_err();
        assert!(!err.contains('\n'), "{err}");
    }
    for i in [13, 40, bytes.len() / 2, bytes.len() - 20, bytes.len() - 1] {
        let mut bad = bytes.clone();
        bad[i] ^= 0x10;
        let err = Checkpoint::from_bytes(&bad).unwrap_err();
        assert!(err.contains("corrupt"), "byte {i}: {err}");
    }
    let mut other = bytes.clone();
    other[8] = 9;
    let err = Checkpoint::from_bytes(&other).unwrap_err();
    assert!(err.contains("version 9"), "{err}");
    assert_eq!(
        Checkpoint::from_bytes(b"PNG not a checkpoint").unwrap_err(),
        "not a candela checkpoint"
    );
}

#[test]
fn other_settings_or_scenes_are_named() {
    let c = checkpoint();
    let same = c.settings.clone();
    assert_eq!(c.check_matches(c.scene_hash, &same), Ok(()));
    // How the work runs or when it stops may change.
    let mut faster = same.clone();
    faster.run.threads = 3;
    faster.sampling.time = Some(5.0);
    assert_eq!(c.check_matches(c.scene_hash, &faster), Ok(()));
    let mut seed = same.clone();
    seed.sampling.seed = 8;
    let err = c
        .check_matches(c.scene_hash, &seed)
        .unwrap_err()
        .to_string();
    assert!(err.contains("seed = 7 in the checkpoint, 8 here"), "{err}");
    let err = c.check_matches(ContentHash([1, 3]), &same).unwrap_err();
    assert!(err.to_string().contains("another scene"), "{err}");
}

#[test]
fn the_sample_target_may_be_raised_not_lowered() {
    let c = checkpoint();
    let target = c.settings.sampling.spp();
    let mut more = c.settings.clone();
    more.sampling.spp = Some(target * 4);
    assert_eq!(c.check_matches(c.scene_hash, &more), Ok(()));
    let mut fewer = c.settings.clone();
    fewer.sampling.spp = Some(target - 1);
    let err = c
        .check_matches(c.scene_hash, &fewer)
        .unwrap_err()
        .to_string();
    let expect = format!("spp = {target} in the checkpoint, {} here", target - 1);
    assert!(err.contains(&expect) && err.contains("not fewer"), "{err}");
}
