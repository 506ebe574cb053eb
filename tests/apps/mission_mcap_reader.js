#!/usr/bin/env node
// An independent reader of the mission's MCAP log: @mcap/core (Foxglove's own
// TypeScript library, npm) reads `ferret explore --retrieve --out DIR`'s mission.mcap
// (or, with MODE "mission", `ferret mission`'s on the two_sites world) twice — streamed record by record with every CRC checked, and through the summary
// and chunk indexes as Foxglove opens a file — and the messages must decode as the
// Foxglove types their schemas name. Exits 77 (ctest: skipped) without @mcap/core.
//   node mission_mcap_reader.js FERRET_BINARY SOURCE_DIR NODE_MODULES_DIR [MODE]
'use strict';
const { execFileSync } = require('child_process');
const fs = require('fs');
const os = require('os');
const path = require('path');

const [ferret, source, modules, mode = 'explore'] = process.argv.slice(2);
const whole = mode === 'mission';
const frame = whole ? 'world' : 'map';
let mcap;
try {
  mcap = require(path.join(modules, '@mcap', 'core'));
} catch (e) {
  console.log(`@mcap/core not found in ${modules}: skipped`);
  process.exit(77);
}

let failures = 0;
function check(ok, what) {
  if (!ok) {
    console.log(`FAIL: ${what}`);
    failures++;
  }
}

async function main() {
  const out = path.join(fs.mkdtempSync(path.join(os.tmpdir(), 'ferret-mcap-')), 'run');
  if (whole)
    execFileSync(ferret, ['mission', '--world', path.join(source, 'examples/worlds/two_sites.yaml'),
      '--seed', '1', '-q', '--out', out]);
  else
    execFileSync(ferret, ['explore', '--map', path.join(source, 'examples/maps/sparse.yaml'),
      '--start', '1,4,0', '--object', '9,6', '--retrieve', '--seed', '1', '--out', out]);
  const bytes = fs.readFileSync(path.join(out, 'mission.mcap'));

  // 1. Streamed, every record, CRCs validated.
  const stream = new mcap.McapStreamReader({ validateCrcs: true });
  stream.append(bytes);
  const schemas = new Map(), channels = new Map(), counts = new Map();
  let record, streamed = 0, sawFooter = false, lastTime = new Map();
  while ((record = stream.nextRecord()) !== undefined) {
    if (record.type === 'Schema') schemas.set(record.id, record);
    if (record.type === 'Channel') channels.set(record.id, record);
    if (record.type === 'Message') {
      streamed++;
      const ch = channels.get(record.channelId);
      check(ch !== undefined, `message on unknown channel ${record.channelId}`);
      counts.set(ch.topic, (counts.get(ch.topic) || 0) + 1);
      const prev = lastTime.get(ch.topic);
      check(prev === undefined || record.logTime >= prev, `${ch.topic} goes back in time`);
      lastTime.set(ch.topic, record.logTime);
      const msg = JSON.parse(Buffer.from(record.data).toString('utf8'));
      const schema = schemas.get(ch.schemaId).name;
      if (schema === 'foxglove.FrameTransform')
        check(msg.parent_frame_id === frame && (msg.child_frame_id === 'ugv' || (whole && msg.child_frame_id === 'uav')) &&
              Math.abs(Math.hypot(msg.rotation.x, msg.rotation.y, msg.rotation.z, msg.rotation.w) - 1) < 1e-9,
              `a FrameTransform ${frame} -> robot with a unit quaternion`);
      if (schema === 'foxglove.Grid') {
        const cells = Buffer.from(msg.data, 'base64').length;
        check(cells % msg.column_count === 0 && cells === msg.row_stride * (cells / msg.column_count),
              'grid data fills whole rows');
        check(msg.fields.length === 1 && msg.fields[0].type === 1, 'one uint8 field');
      }
      if (schema === 'foxglove.Log') check(typeof msg.message === 'string' && msg.level === 2, 'a log line');
      if (schema === 'foxglove.SceneUpdate')
        check(msg.entities.length === 1 && msg.entities[0].frame_id === frame &&
              (msg.entities[0].lines.length + msg.entities[0].spheres.length) === 1,
              `a scene entity in the ${frame} frame`);
      const stamp = schema === 'foxglove.SceneUpdate' ? msg.entities[0].timestamp : msg.timestamp;
      check(Math.abs(Number(record.logTime) - (stamp.sec * 1e9 + stamp.nsec)) < 1000,
            `${ch.topic}: log time = the message's timestamp`);
    }
    if (record.type === 'Footer') sawFooter = true;
  }
  check(stream.done(), 'the stream reader reached the end');
  check(sawFooter, 'a footer');
  const topics = whole ? ['/tf', '/uav/path', '/maps/shed_void/G', '/maps/shed_void/O', '/maps/kiln_void/G',
                          '/detections', '/log']
                       : ['/tf', '/ugv/path', '/maps/G', '/maps/O', '/objects', '/log'];
  for (const topic of topics)
    check((counts.get(topic) || 0) > 0, `messages on ${topic}`);
  for (const s of schemas.values())
    check(s.name.startsWith('foxglove.') && s.encoding === 'jsonschema', `schema ${s.name}`);

  // 2. Indexed, as Foxglove opens a file: the summary's counts and every message again.
  const readable = {
    size: async () => BigInt(bytes.length),
    read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
  };
  const reader = await mcap.McapIndexedReader.Initialize({ readable });
  check(reader.statistics !== undefined, 'statistics in the summary');
  check(Number(reader.statistics.messageCount) === streamed, 'statistics count every message');
  check(reader.chunkIndexes.length > 0, 'chunk indexes');
  let indexed = 0;
  for await (const m of reader.readMessages()) indexed++;
  check(indexed === streamed, `indexed read finds every message (${indexed} of ${streamed})`);
  const logs = [];
  for await (const m of reader.readMessages({ topics: ['/log'] }))
    logs.push(JSON.parse(Buffer.from(m.data).toString('utf8')).message);
  check(logs.length > 0 && logs[logs.length - 1].includes('-> done'), 'the last transition ends in done');
  for (const step of whole ? ['search -> approach', 'lower -> ugv_ops', 'explore -> track', 'deliver -> drop']
                           : ['explore -> track'])
    check(logs.some((l) => l.includes(step)), `${step} logged`);

  console.log(`${streamed} messages on ${counts.size} topics, ${reader.chunkIndexes.length} chunks; ` +
              `${failures} failures`);
  process.exit(failures === 0 ? 0 : 1);
}

main().catch((e) => {
  console.log(`FAIL: ${e.stack || e}`);
  process.exit(1);
});
