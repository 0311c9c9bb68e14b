#!/usr/bin/env bash
# test_reliability_inputs — hostile inputs are refused with exit 2 and one line that says what
# is wrong: a DEM sample beyond +-1e5 m (naming the sample; a no-data sample is still filled by
# the documented rule), a JSON key given twice anywhere in a scene (naming its path: an
# object twice, a member twice, a key twice inside an object of the list), a NaN literal, JSON
# nested past cJSON's limit, a group of parameters given a non-object, the PNG/EXR heightmap
# keys or a second band with a georeferenced DEM, and terrain.heightmap_detail without a file.
# labels: reliability cli
#
# Oracles: include/atmo/dem.h (ATMO_DEM_MAX_HEIGHT_M, the no-data rule: a missing sample takes
# the mean of its known 8-neighbours), RFC 8259 (JSON numbers have no NaN or Infinity; an
# object's names should be unique, and atmo requires it), cJSON's CJSON_NESTING_LIMIT (1000),
# and the refusal contract of tests/support_cli.sh (exit 2, one stderr line, nothing written).
# The DEMs are ESRI ASCII grids read through GDAL, with a .prj that makes them metric (UTM);
# without GDAL the DEM cases are skipped.
set -u
atmo=$1
. "${ATMO_SOURCE_DIR:-$(dirname "$0")/..}/tests/support_cli.sh"
cli_begin
export ATMO_CACHE_DIR=$work/cache TMPDIR=$work/tmp
mkdir -p "$TMPDIR"
r=(render --width 8 --height 8 --samples 1 --quiet --output out/a.pfm)

# grid NAME ROW2: a 4 x 4 ASCII grid whose second row is ROW2, nodata -9999, in UTM zone 33N
grid() {
    printf 'ncols 4\nnrows 4\nxllcorner 0\nyllcorner 0\ncellsize 30\nNODATA_value -9999\n10 20 30 40\n%s\n10 20 30 40\n10 20 30 40\n' "$2" >"$1.asc"
    echo 'PROJCS["WGS_1984_UTM_Zone_33N",GEOGCS["GCS_WGS_1984",DATUM["D_WGS_1984",SPHEROID["WGS_1984",6378137.0,298.257223563]],PRIMEM["Greenwich",0.0],UNIT["Degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],PARAMETER["False_Easting",500000.0],PARAMETER["False_Northing",0.0],PARAMETER["Central_Meridian",15.0],PARAMETER["Scale_Factor",0.9996],PARAMETER["Latitude_Of_Origin",0.0],UNIT["Meter",1.0]]' >"$1.prj"
}
if "$atmo" dem info --help 2>&1 | grep -q GeoTIFF && ldd "$atmo" | grep -q gdal; then
    grid huge "10 1e30 30 40"
    refused "a DEM sample at 1e30 m" "huge.asc: the sample at column 1, row 1 is 1e\+30 m, beyond \+-100000 m" dem info huge.asc
    refused "render with it" "the sample at column 1, row 1 is 1e\+30 m" "${r[@]}" --set terrain.heightmap_file=huge.asc
    grid deep "10 20 -2e5 40"
    refused "a DEM sample at -2e5 m" "column 2, row 1 is -200000 m" dem info deep.asc
    grid hole "10 -9999 30 40"
    "$atmo" dem info hole.asc --json >hole.json 2>hole.err
    # the hole at (1, 1) takes the mean of its 8 neighbours: (10+20+30 + 10+30 + 10+20+30) / 8
    python3 -c "
import json, sys
d = json.load(open('hole.json'))
sys.exit(not (d['nodata_filled'] == 1 and d['min_m'] == 10 and d['max_m'] == 40))" && ok ||
        bad "a no-data sample is not filled by the rule: $(cat hole.json hole.err)"
    # a GeoTIFF-like (GDAL) DEM: the PNG/EXR keys and a second band are refused, not ignored
    grid plain "10 20 30 40"
    refused "extent key with a georeferenced DEM" "plain.asc \(AAIGrid\) carries its own extent.*heightmap_file_extent_m is for PNG and EXR" \
        dem info plain.asc --set terrain.heightmap_file_extent_m=5000
    refused "offset key with a georeferenced DEM" "heightmap_file_offset_m is for PNG and EXR" \
        dem info plain.asc --set terrain.heightmap_offset_m=100
    {
        echo '<VRTDataset rasterXSize="4" rasterYSize="4"><GeoTransform>0, 30, 0, 120, 0, -30</GeoTransform>'
        echo "<SRS>$(sed 's/"/\&quot;/g' plain.prj)</SRS>"
        for b in 1 2 3; do
            echo "<VRTRasterBand dataType=\"Float32\" band=\"$b\"><SimpleSource><SourceFilename relativeToVRT=\"1\">plain.asc</SourceFilename><SourceBand>1</SourceBand></SimpleSource></VRTRasterBand>"
        done
        echo '</VRTDataset>'
    } >three.vrt
    refused "a DEM with three bands" "three.vrt \(VRT\) has 3 bands; a heightmap is one band" dem info three.vrt
fi

# terrain.heightmap_detail without a heightmap file
refused "heightmap_detail without a heightmap" "terrain.heightmap_detail=true adds detail below a heightmap file's cells" \
    "${r[@]}" --set terrain.heightmap_detail=true

# duplicate keys, with their paths
echo '{"sun": {"zenith_deg": 60, "zenith_deg": 70}}' >dup_member.json
refused "a member twice" "dup_member.json: the key 'sun.zenith_deg' is given twice" "${r[@]}" --scene dup_member.json
echo '{"sun": {"zenith_deg": 60}, "camera": {"fov_deg": 50}, "sun": {"azimuth_deg": 10}}' >dup_object.json
refused "an object twice" "dup_object.json: the key 'sun' is given twice" "${r[@]}" --scene dup_object.json
cat >dup_list.json <<'JSON'
{"objects": [{"type": "sphere", "center_m": [0, 1, 5], "radius_m": 1},
             {"type": "sphere", "on_terrain": false, "center_m": [0, 1, 9], "radius_m": 1, "on_terrain": true}]}
JSON
refused "a key twice in a listed object" "the key 'objects\[1\].on_terrain' is given twice" "${r[@]}" --scene dup_list.json
refused "a key twice in --set objects" "the key 'objects\[0\].type' is given twice" "${r[@]}" \
    --set 'objects=[{"type": "sphere", "type": "box", "center_m": [0, 1, 5], "radius_m": 1}]'

# messages that say what is wrong
echo '{"sun": {"zenith_deg": NaN}}' >nan.json
refused "a NaN literal" "'NaN' is not a JSON number" "${r[@]}" --scene nan.json
python3 -c "print('{\"sun\": ' + '[' * 1100 + ']' * 1100 + '}')" >deep.json
refused "nesting past the limit" "nested more than 1000 levels deep" "${r[@]}" --scene deep.json
echo '{"sun": null}' >sun_null.json
refused "a group given null" "'sun' in sun_null.json is a group of parameters and needs an object" "${r[@]}" --scene sun_null.json

cli_end test_reliability_inputs
