#pragma once
/// \file
/// The host functions a compiled SimTwo script calls, by number: the support unit
/// (pascal/s2simtwo.pas) gets one Pascal constant `h<Name>` per entry, generated from this list,
/// and the host (script_controller.cpp) dispatches on it.

// One entry a line, in the support unit's order.
// clang-format off
#define S2SIM_PASCAL_HOST_FUNCTIONS(X) \
  X(WriteLn) \
  X(KeyPressed) \
  X(ScriptPeriod) \
  X(GetSceneConstant) \
  X(SetRCValue) \
  X(GetRCValue) \
  X(GetRCText) \
  X(RCButtonPressed) \
  X(ClearButtons) \
  X(RefreshSheets) \
  X(GetRobotIndex) \
  X(GetSolidIndex) \
  X(GetSensorIndex) \
  X(GetAxisIndex) \
  X(GetGlobalSensorIndex) \
  X(GetThingIndex) \
  X(GetThingsCount) \
  X(SetAxisVoltageRef) \
  X(SetAxisSpeedRef) \
  X(SetAxisPosRef) \
  X(SetAxisTorqueRef) \
  X(GetAxisPosRef) \
  X(GetAxisSpeedRef) \
  X(GetAxisOdo) \
  X(GetAxisPos) \
  X(GetAxisSpeed) \
  X(GetAxisI) \
  X(GetAxisU) \
  X(GetAxisTorque) \
  X(SetMotorActive) \
  X(IsMotorActive) \
  X(SetMotorControllerState) \
  X(GetMotorControllerState) \
  X(GetMotorPars) \
  X(SetMotorPars) \
  X(GetSensorVal) \
  X(GetSensorValues) \
  X(SetSensorVin) \
  X(GetGlobalSensorVal) \
  X(GetGlobalSensorValues) \
  X(SetRobotPos) \
  X(GetRobotX) \
  X(GetRobotY) \
  X(GetRobotTheta) \
  X(GetRobotVx) \
  X(GetRobotVy) \
  X(GetRobotW) \
  X(GetSolidPos) \
  X(GetSolidTheta) \
  X(GetSolidRotMat) \
  X(GetSolidLinearVel) \
  X(SetSolidPos) \
  X(SetSolidRotationMat) \
  X(SetSolidLinearVel) \
  X(SetSolidAngularVel) \
  X(SetSolidColor) \
  X(SetShellTag) \
  X(GetShellTag) \
  X(SetThingPos) \
  X(GetThingPos) \
  X(GetThingColor) \
  X(GetObstaclePos) \
  X(AddOBstacleBox) \
  X(SetShellColor) \
  X(SetObstacleColor) \
  X(SetSensorColor) \
  X(DeleteObstacle) \
  X(SetObstaclePos) \
  X(SetObstacleRotationMat) \
  X(SetSolidSize) \
  X(SetSolidMass) \
  X(SetThingSize) \
  X(SetSolidSurfaceFriction) \
  X(SetThingSurfaceMu) \
  X(Fire) \
  X(AddThingBox) \
  X(AddThingSphere) \
  X(AddThingCylinder) \
  X(DeleteThing) \
  X(ClearThings) \
  X(MeshThing) \
  X(ClearObstacles) \
  X(ChartSeriesSetCount) \
  X(ChartSeriesSetColor) \
  X(ChartSeriesClear) \
  X(ChartSeriesAddXY) \
  X(AddTrailNode) \
  X(ClearTrail) \
  X(WriteUDPData) \
  X(UDPDataArrived) \
  X(WriteComPort) \
  X(ReadComPort) \
  X(HUDText) \
  X(GetSolidAngularVel) \
  X(GetSolidMass) \
  X(SetSolidForce) \
  X(SetThingColor) \
  X(GetThingRotMat) \
  X(SetThingRotationMat) \
  X(GetThingAngularVel) \
  X(GetThingSpeed) \
  X(SetThingSpeed) \
  X(SetThingLinearVel) \
  X(SetThingAngularVel) \
  X(SetThingForce) \
  X(SetThingForceAtRelPos) \
  X(SetThingRelForce) \
  X(SetThingRelForceAtRelPos) \
  X(GetObstacleIndex) \
  X(SetGlobalSensorVin) \
  X(GetAxisUIPower) \
  X(SetTrailColor) \
  X(DelTrailNode) \
  X(ChartSetAxisMinMax) \
  X(ChartSeriesGetCount) \
  X(ChartSeriesCreate) \
  X(ChartSeriesDeleteAll) \
  X(SetRCBackColor) \
  X(ReadUDPPacket) \
  X(GetUDPPacketCount) \
  X(SetAxisSpring) \
  X(SetFrictionDef) \
  X(GetFrictionDef) \
  X(SetMotorControllerPars) \
  X(GetMotorControllerPars) \
  X(SetMotorControllerMode) \
  X(GetMotorControllerMode) \
  X(GetAxisEnergy) \
  X(ResetAxisEnergy) \
  X(CloseSimTwo) \
  X(getModbusCoil) \
  X(getModbusInput) \
  X(setModbusCoil) \
  X(setModbusInput) \
  X(GetSolidColor) \
  X(GetSolidSize) \
  X(GetThingSize) \
  X(GetSolidCenterOfMass) \
  X(GetRobotCenterOfMass) \
  X(GetSolidTag) \
  X(SetSolidTag) \
  X(GetObstacleColor) \
  X(GetObstacleRotMat) \
  X(AxisCount) \
  X(AxisJoint) \
  X(ScriptFolder) \
  X(SetBeltSpeed) \
  X(GetBeltSpeed) \
  X(GetShellPos) \
  X(GetShellColor) \
  X(SetSprayGunOn) \
  X(SetSprayGunOff) \
  X(GetPaintGunMinDist) \
  X(GetPaintTargetExtents) \
  X(ResetPaintTargetPaint) \
  X(SetPaintTargetPaintMode) \
  X(GetPaintTargetTriangles) \
  X(SetResultTrianglesColor) \
  X(CalculateSprayThicknessHistogram) \
  X(CalculateAvgSprayThickness) \
  X(CalculateSDSprayThickness) \
  X(CalculatePosAvgSprayThickness) \
  X(CalculatePosSDSprayThickness) \
  X(CalculatePosMinSprayThickness) \
  X(CalculateMinSprayThickness) \
  X(CalculateMaxSprayThickness) \
  X(CalculateSprayCoverage) \
  X(GetCameraPixel) \
  X(CanvasOf) \
  X(CanvasOp)
// clang-format on

namespace s2sim::pascal {

enum class HostFn : int {
#define S2SIM_PASCAL_ENUM(name) name,
  S2SIM_PASCAL_HOST_FUNCTIONS(S2SIM_PASCAL_ENUM)
#undef S2SIM_PASCAL_ENUM
      count
};

inline constexpr const char* kHostFnNames[] = {
#define S2SIM_PASCAL_NAME(name) #name,
    S2SIM_PASCAL_HOST_FUNCTIONS(S2SIM_PASCAL_NAME)
#undef S2SIM_PASCAL_NAME
};

}  // namespace s2sim::pascal
